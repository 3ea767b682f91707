// Mutation testing: the operators on IL lines, a run on a small cell whose cases check
// part of the program (killed, survived, equivalent-suspect, not loaded as defined in
// docs/testing-your-cell.md), the same report for any -j, and the demo's run.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "../core/run_tool.h"
#include "../core/tool_text.h"
#include "program_lines.h"
#include "plc_cell/core/il_parser.h"
#include "plc_cell/mutation/mutant.h"

using namespace plc_cell::mutation;
using plc_cell::testing::has;
using plc_cell::testing::program_lines;
using plc_cell::testing::run_tool;
using plc_cell::testing::slurp;
using plc_cell::testing::ToolResult;

namespace {

const std::string kSrc = PLC_CELL_SOURCE_DIR;

// The mutants of a program's lines (from: the first line listed), "line operator: change".
std::vector<std::string> changes(const std::string& text, int from = 1) {
  const plc_cell::FunctionTable fns = plc_cell::FunctionTable::with_core_functions();
  const plc_cell::Program p = plc_cell::parse_program(text, "t.il", fns);
  std::vector<std::string> out;
  for (const Mutant& m : mutants(program_lines(text), p, fns))
    if (m.line >= from) out.push_back(std::to_string(m.line) + " " + m.op + ": " + m.change());
  return out;
}

// Y0 follows X0 and X1 (X1 by an OR nobody tests); T0 (0.1 s base... 10 ms) on X2 sets M5.
const char* kProgram =
    "ORG X0      ; start\n"
    "OR  X1\n"
    "OUT Y0\n"
    "ORG X2\n"
    "TMR T0 50\n"
    "ORG T0\n"
    "SET Y1\n"
    "END\n";

}  // namespace

TEST(Mutants, EveryOperatorOnItsInstructions) {
  EXPECT_EQ(changes("ORG M1925\nAND X3 ; why\nLD NOT X4\nANDLD\nOUT Y0\nORG TU M1\nOR TD Y2\nOUT Y3\nEND\n", 2),
            (std::vector<std::string>{
                "2 invert contact: AND X3 \u2192 AND NOT X3", "2 AND/OR: AND X3 \u2192 OR X3", "2 edge: AND X3 \u2192 AND TU X3",
                "3 invert contact: LD NOT X4 \u2192 LD X4", "4 ANDLD/ORLD: ANDLD \u2192 ORLD",
                "5 delete coil: OUT Y0 \u2192 (deleted)",
                "6 edge: ORG TU M1 \u2192 ORG TD M1", "6 edge: ORG TU M1 \u2192 ORG M1",
                "7 AND/OR: OR TD Y2 \u2192 AND TD Y2", "7 edge: OR TD Y2 \u2192 OR TU Y2", "7 edge: OR TD Y2 \u2192 OR Y2",
                "8 delete coil: OUT Y3 \u2192 (deleted)"}));
  EXPECT_EQ(changes("ORG X0\nLD X1\nORLD\nSET Y1\nRST C0\nOUT NOT M3\nEND\n", 3),
            (std::vector<std::string>{"3 ANDLD/ORLD: ORLD \u2192 ANDLD",
                                      "4 SET/RST: SET Y1 \u2192 RST Y1", "4 delete coil: SET Y1 \u2192 (deleted)",
                                      "5 delete coil: RST C0 \u2192 (deleted)", "6 delete coil: OUT NOT M3 \u2192 (deleted)"}));
  EXPECT_EQ(changes("ORG X0\nTMR T50 15\nCTR C0 1\nTMR T1 R5\nEND\n", 2),
            (std::vector<std::string>{"2 preset: TMR T50 15 \u2192 TMR T50 16", "2 preset: TMR T50 15 \u2192 TMR T50 14",
                                      "2 preset: TMR T50 15 \u2192 TMR T50 30", "2 preset: TMR T50 15 \u2192 TMR T50 7",
                                      "3 preset: CTR C0 1 \u2192 CTR C0 2"}));
  EXPECT_EQ(changes("ORG X0\nFUN 17 CMP Sa=R0 Sb=5 EQ=M51\nEND\n", 2),
            (std::vector<std::string>{"2 constant: FUN 17 CMP Sa=R0 Sb=5 EQ=M51 \u2192 FUN 17 CMP Sa=R0 Sb=6 EQ=M51",
                                      "2 constant: FUN 17 CMP Sa=R0 Sb=5 EQ=M51 \u2192 FUN 17 CMP Sa=R0 Sb=4 EQ=M51",
                                      "2 comparison: FUN 17 CMP Sa=R0 Sb=5 EQ=M51 \u2192 FUN 17 CMP Sa=R0 Sb=5 GT=M51",
                                      "2 comparison: FUN 17 CMP Sa=R0 Sb=5 EQ=M51 \u2192 FUN 17 CMP Sa=R0 Sb=5 LT=M51"}));
  const std::vector<std::string> lines = {"ORG X0", "OUT Y0 ; the motor", "END"};
  const auto fns = plc_cell::FunctionTable::with_core_functions();
  const auto p = plc_cell::parse_program("ORG X0\nOUT Y0\nEND\n", "t.il", fns);
  EXPECT_EQ(plc_cell::mutation::apply(lines, mutants(lines, p, fns).at(0)), "ORG NOT X0\nOUT Y0 ; the motor\nEND\n");
  EXPECT_EQ(plc_cell::mutation::apply(lines, mutants(lines, p, fns).back()), "ORG X0\n\nEND\n");
}

TEST(Mutation, KilledSurvivedAndEquivalentOnASmallCell) {
  const std::string dir = ::testing::TempDir() + "/mutation_small";
  std::system(("mkdir -p " + dir).c_str());
  std::ofstream(dir + "/cell.il") << kProgram;
  std::ofstream(dir + "/cell.yaml") << "cell: {name: t, program: cell.il}\nplc: {scan_period: 0.001}\n";
  // X0 turns Y0 on (checked, but not that Y0 was off before); X1 is never pressed; T0's
  // preset is checked to the scan.
  std::ofstream(dir + "/s.scenario.yaml") << "cell: cell.yaml\ncases:\n"
                                             "  - name: start\n    steps:\n"
                                             "      - at: 100ms\n        set: {X0: on}\n"
                                             "      - after: 10ms\n        expect: Y0\n"
                                             "  - name: timer\n    steps:\n"
                                             "      - set: {X2: on}\n      - expect: not Y1\n        stays: 499ms\n"
                                             "      - after: 1ms\n        expect: Y1\n";
  const std::string json = dir + "/m.json", html = dir + "/html";
  const ToolResult r = run_tool("test " + dir + "/s.scenario.yaml --mutate --mutate-json " + json + " --coverage-html " + html);
  EXPECT_EQ(r.status, 0) << r.out;
  const std::string p = dir + "/cell.il";
  EXPECT_TRUE(has(r.out, "mutation testing on the native engine (the original program's cases on the interpreter, "
                         "recording what they execute)\nmutation testing of " + p + ": 16 mutants, 2 cases each\n"))
      << r.out;
  // OR NOT X1 holds Y0 on from the first scan: Y0 differs, but no case checks that Y0 is
  // off before X0 (not checked). OR -> AND keeps Y0 off with X0: killed. OR TU X1 changes
  // nothing while X1 stays off, but the exhaustive run over X0, X1 holds X1 on for two
  // scans: Y0 drops (not observed). ORG TU T0 sets the latch Y1 on T0's first scan as
  // ORG T0 does, whatever the inputs: the one equivalent-suspect. 13 / (13 + 2) = 86.7 %.
  EXPECT_TRUE(has(r.out, "  killed 13, survived 2 (not executed 0, not observed 1, not checked 1), "
                         "equivalent-suspect 1, not loaded 0: score 86.7 %\n")) << r.out;
  EXPECT_TRUE(has(r.out, "  network 1 (line 1): 4/6 killed\n")) << r.out;
  EXPECT_TRUE(has(r.out, "  network 3 (line 6): 3/3 killed, 1 equivalent-suspect\n")) << r.out;
  EXPECT_TRUE(has(r.out, p + ":2: OR X1 \u2192 OR NOT X1 in network 1 (line 1): survived: no case checks it "
                             "(executed by every case)\n")) << r.out;
  EXPECT_TRUE(has(r.out, p + ":2: OR X1 \u2192 OR TU X1 in network 1 (line 1): survived: executed (by every case), "
                             "but no case sees a difference; an input search tells it apart: Y0 OFF, the original's ON "
                             "at 0.012 s of the exhaustive run over X0, X1 (one scan a step)\n")) << r.out;
  EXPECT_TRUE(has(r.out, p + ":6: ORG T0 \u2192 ORG TU T0 in network 3 (line 6): equivalent-suspect: no case and no "
                             "input search tells it apart (every combination of X2 (one scan a step, then 1.000 s), "
                             "then 10 exploration runs of 10.000 s (inputs X0, X1, X2, seed 1))\n")) << r.out;
  const std::string j = slurp(json);
  EXPECT_TRUE(has(j, "{\"line\": 7, \"network\": 3, \"network_line\": 6, \"operator\": \"SET/RST\", \"from\": \"SET Y1\", "
                     "\"to\": \"RST Y1\", \"status\": \"killed\", \"survival\": null, \"killed_by\": \"timer\", "
                     "\"told_apart\": null, \"searched\": null, \"executed_by\": [\"start\", \"timer\"]}")) << j;
  EXPECT_TRUE(has(j, "\"survived\": 2, \"survived_not_executed\": 0, \"survived_not_observed\": 1, "
                     "\"survived_not_checked\": 1, \"equivalent_suspect\": 1")) << j;
  EXPECT_TRUE(has(slurp(html + "/index.html"), "<h2>Mutation testing</h2>"));
  // The same report with two worker processes (and the same outputs asked for).
  const ToolResult r2 =
      run_tool("test " + dir + "/s.scenario.yaml --mutate -j 2 --mutate-json " + json + "2 --coverage-html " + html + "2");
  EXPECT_EQ(r2.out, r.out);
  EXPECT_EQ(slurp(json + "2"), j);
  // A budget: evenly spaced mutants, the count said.
  const ToolResult b = run_tool("test " + dir + "/s.scenario.yaml --mutate --mutate-budget 5");
  EXPECT_TRUE(has(b.out, ": 5 mutants (of 16), 2 cases each\n")) << b.out;
  // -k: the selected cases only. Without "start", X0 and X1 stay OFF: the two mutants that
  // turn Y0 on (ORG NOT X0, OR NOT X1) are seen and not checked; the four that leave it
  // OFF with X0 and X1 OFF (ORG TU X0, OR -> AND, OR TU X1, OUT Y0 deleted) the search
  // tells apart. 9 / (9 + 6) = 60.0 %.
  const ToolResult k = run_tool("test " + dir + "/s.scenario.yaml --mutate -k timer --engine lockstep");
  EXPECT_TRUE(has(k.out, "mutation testing on the lockstep engine (")) << k.out;
  EXPECT_TRUE(has(k.out, ": 16 mutants, 1 case each\n  killed 9, survived 6 (not executed 0, not observed 4, "
                         "not checked 2), equivalent-suspect 1, not loaded 0: score 60.0 %\n")) << k.out;
  EXPECT_TRUE(has(k.out, "  network 1 (line 1): 0/6 killed\n")) << k.out;
}

TEST(Mutation, TheDemoReportsAScoreAndItsSurvivors) {
  const std::string f = kSrc + "/examples/conveyor/conveyor.scenario.yaml";
  const std::string json = ::testing::TempDir() + "/mutation_demo.json";
  const ToolResult r = run_tool("test " + f + " --mutate -j 2 --mutate-json " + json);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, "mutation testing of " + kSrc + "/examples/conveyor/conveyor.il: 57 mutants, 7 cases each\n"))
      << r.out;
  EXPECT_TRUE(has(r.out, ": score ")) << r.out;
  EXPECT_TRUE(has(r.out, kSrc + "/examples/conveyor/conveyor.il:20: OR Y1 \u2192 OR TU Y1 in network 2 (line 18): "
                                "survived: no case checks it")) << r.out;
  // Line 43, ORG M1925, runs in every scan of every case (its contact records nothing of
  // its own: M1925 cannot change).
  const std::string every = "\"executed_by\": [\"starts by itself and runs the belt\", \"a part is picked, released and "
                            "counted\", \"counts every part[parts=1,at=4s]\", \"counts every part[parts=2,at=9s]\", "
                            "\"counts every part[parts=3,at=14s]\", \"the stop button stops the line and the start button "
                            "starts it\", \"a part held at the sensor keeps the belt stopped while the stopper is forced "
                            "up\"]}";
  EXPECT_TRUE(has(slurp(json), "{\"line\": 43, \"network\": 8, \"network_line\": 43, \"operator\": \"invert contact\", "
                               "\"from\": \"ORG M1925\", \"to\": \"ORG NOT M1925\", \"status\": \"killed\", \"survival\": "
                               "null, \"killed_by\": \"a part is picked, released and counted\", \"told_apart\": null, "
                               "\"searched\": null, " + every)) << slurp(json);
}
