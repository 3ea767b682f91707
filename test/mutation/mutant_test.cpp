// Mutation testing: the operators on IL lines, a run on a small cell whose cases check
// part of the program (killed, survived, equivalent-suspect, not loaded as defined in
// docs/testing-your-cell.md), the same report for any -j, and the demo's run.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "../core/run_tool.h"
#include "../core/tool_text.h"
#include "plc_cell/mutation/mutant.h"

using namespace plc_cell::mutation;
using plc_cell::testing::has;
using plc_cell::testing::run_tool;
using plc_cell::testing::slurp;
using plc_cell::testing::ToolResult;

namespace {

const std::string kSrc = PLC_CELL_SOURCE_DIR;

std::vector<std::string> changes(const std::vector<std::string>& lines) {
  std::vector<std::string> out;
  for (const Mutant& m : mutants(lines)) out.push_back(std::to_string(m.line) + " " + m.op + ": " + m.change());
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
  EXPECT_EQ(changes({"AND X3 ; why", "LD NOT X4", "ORG TU M1", "OR TD Y2"}),
            (std::vector<std::string>{
                "1 invert contact: AND X3 \u2192 AND NOT X3", "1 AND/OR: AND X3 \u2192 OR X3", "1 edge: AND X3 \u2192 AND TU X3",
                "2 invert contact: LD NOT X4 \u2192 LD X4",
                "3 edge: ORG TU M1 \u2192 ORG TD M1", "3 edge: ORG TU M1 \u2192 ORG M1",
                "4 AND/OR: OR TD Y2 \u2192 AND TD Y2", "4 edge: OR TD Y2 \u2192 OR TU Y2", "4 edge: OR TD Y2 \u2192 OR Y2"}));
  EXPECT_EQ(changes({"ANDLD", "ORLD", "SET Y1", "RST C0", "OUT NOT M3"}),
            (std::vector<std::string>{"1 ANDLD/ORLD: ANDLD \u2192 ORLD", "2 ANDLD/ORLD: ORLD \u2192 ANDLD",
                                      "3 SET/RST: SET Y1 \u2192 RST Y1", "3 delete coil: SET Y1 \u2192 (deleted)",
                                      "4 delete coil: RST C0 \u2192 (deleted)", "5 delete coil: OUT NOT M3 \u2192 (deleted)"}));
  EXPECT_EQ(changes({"TMR T50 15", "CTR C0 1", "TMR T1 R5"}),
            (std::vector<std::string>{"1 preset: TMR T50 15 \u2192 TMR T50 16", "1 preset: TMR T50 15 \u2192 TMR T50 14",
                                      "1 preset: TMR T50 15 \u2192 TMR T50 30", "1 preset: TMR T50 15 \u2192 TMR T50 7",
                                      "2 preset: CTR C0 1 \u2192 CTR C0 2"}));
  EXPECT_EQ(changes({"FUN 17 CMP Sa=R0 Sb=5 EQ=M51"}),
            (std::vector<std::string>{"1 constant: FUN 17 CMP Sa=R0 Sb=5 EQ=M51 \u2192 FUN 17 CMP Sa=R0 Sb=6 EQ=M51",
                                      "1 constant: FUN 17 CMP Sa=R0 Sb=5 EQ=M51 \u2192 FUN 17 CMP Sa=R0 Sb=4 EQ=M51",
                                      "1 comparison: FUN 17 CMP Sa=R0 Sb=5 EQ=M51 \u2192 FUN 17 CMP Sa=R0 Sb=5 GT=M51",
                                      "1 comparison: FUN 17 CMP Sa=R0 Sb=5 EQ=M51 \u2192 FUN 17 CMP Sa=R0 Sb=5 LT=M51"}));
  const std::vector<std::string> lines = {"ORG X0", "OUT Y0 ; the motor", "END"};
  EXPECT_EQ(plc_cell::mutation::apply(lines, mutants(lines).at(0)), "ORG NOT X0\nOUT Y0 ; the motor\nEND\n");
  EXPECT_EQ(plc_cell::mutation::apply(lines, mutants(lines).back()), "ORG X0\n\nEND\n");
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
  // OR NOT X1 holds Y0 on from the first scan: no case checks that Y0 is off before X0.
  // OR -> AND keeps Y0 off with X0: killed. OR TU X1 changes nothing while X1 stays off,
  // and ORG TU T0 nothing as SET latches: equivalent-suspects.
  EXPECT_TRUE(has(r.out, "  killed 13, survived 1, equivalent-suspect 2, not loaded 0: score 92.9 %\n")) << r.out;
  EXPECT_TRUE(has(r.out, "  network 1 (line 1): 4/5 killed, 1 equivalent-suspect\n")) << r.out;
  EXPECT_TRUE(has(r.out, p + ":2: OR X1 \u2192 OR NOT X1 survived: no case checks it (executed by every case)\n")) << r.out;
  EXPECT_TRUE(has(r.out, p + ":2: OR X1 \u2192 OR TU X1 equivalent-suspect: every probed value is the same at every "
                             "scan of every case\n")) << r.out;
  EXPECT_TRUE(has(r.out, p + ":6: ORG T0 \u2192 ORG TU T0 equivalent-suspect")) << r.out;
  const std::string j = slurp(json);
  EXPECT_TRUE(has(j, "{\"line\": 7, \"network\": 3, \"operator\": \"SET/RST\", \"from\": \"SET Y1\", \"to\": \"RST Y1\", "
                     "\"status\": \"killed\", \"killed_by\": \"timer\", \"executed_by\": [\"start\", \"timer\"]}")) << j;
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
  // turn Y0 on survive, the four that leave it OFF are equivalent-suspects.
  const ToolResult k = run_tool("test " + dir + "/s.scenario.yaml --mutate -k timer --engine lockstep");
  EXPECT_TRUE(has(k.out, "mutation testing on the lockstep engine (")) << k.out;
  EXPECT_TRUE(has(k.out, ": 16 mutants, 1 case each\n  killed 9, survived 2, equivalent-suspect 5")) << k.out;
  EXPECT_TRUE(has(k.out, "  network 1 (line 1): 0/2 killed, 4 equivalent-suspect\n")) << k.out;
}

TEST(Mutation, TheDemoReportsAScoreAndItsSurvivors) {
  const std::string f = kSrc + "/examples/conveyor/conveyor.scenario.yaml";
  const ToolResult r = run_tool("test " + f + " --mutate -j 2");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, "mutation testing of " + kSrc + "/examples/conveyor/conveyor.il: 57 mutants, 7 cases each\n"))
      << r.out;
  EXPECT_TRUE(has(r.out, ": score ")) << r.out;
  EXPECT_TRUE(has(r.out, kSrc + "/examples/conveyor/conveyor.il:20: OR Y1 \u2192 OR TU Y1 survived: no case checks it"))
      << r.out;
}
