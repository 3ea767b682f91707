// The mutation score does not flatter: a mutant that passes every case is
// equivalent-suspect only when an input search finds no difference either; every other
// one is a survivor, counted, and said to be not executed, not observed or not checked.
// Two suites that check little, their numbers worked out by hand below.
#include <gtest/gtest.h>

#include <fstream>

#include "../core/run_tool.h"
#include "../core/tool_text.h"

using plc_cell::testing::has;
using plc_cell::testing::run_tool;
using plc_cell::testing::ToolResult;

namespace {

// A folder with cell.yaml (1 ms scans), the program and the scenario; the tool's report.
ToolResult mutate(const std::string& name, const std::string& program, const std::string& scenario) {
  const std::string dir = ::testing::TempDir() + "/" + name;
  std::system(("mkdir -p " + dir).c_str());
  std::ofstream(dir + "/cell.il") << program;
  std::ofstream(dir + "/cell.yaml") << "cell: {name: t, program: cell.il}\nplc: {scan_period: 0.001}\n";
  std::ofstream(dir + "/s.scenario.yaml") << "cell: cell.yaml\n" << scenario;
  return run_tool("test " + dir + "/s.scenario.yaml --mutate -j 2");
}

}  // namespace

// Three small networks and one case that checks the AND of the first.
//
//   network 1 (lines 1-3)   ORG X0 / AND X1 / OUT Y0                  6 mutants
//   network 2 (lines 4-8)   ORG X2 / OR X3 / OUT Y1 / OUT Y1 / OUT Y3  8 mutants
//   network 3 (lines 9-11)  ORG X4 / OR X4 / OUT Y2                   6 mutants
//
// The case sets X0 and X1 and expects Y0. Network 1: ORG NOT X0, ORG TU X0 (Y0 for one
// scan), AND NOT X1, AND TU X1 and the deleted OUT Y0 fail it: 5 killed. AND -> OR gives
// Y0 too: no case sees it, X0 alone tells it apart (not observed). Network 2 with X2, X3
// OFF: ORG NOT X2 and OR NOT X3 turn Y1, Y3 on (seen, not checked); ORG TU X2, OR -> AND,
// OR TU X3 and the deleted OUT Y3 change nothing until X2 or X3 is ON (not observed);
// either OUT Y1 deleted leaves the other driving Y1 (equivalent-suspect). Network 3:
// ORG NOT X4 and OR NOT X4 turn Y2 on (not checked); the deleted OUT Y2 shows only with X4
// ON (not observed); ORG TU X4, OR -> AND and OR TU X4 all still give Y2 = X4
// (equivalent-suspect). 15 of the 20 are told apart: 5 killed and 10 survivors,
// 5 / 15 = 33.3 %. Leaving out the 6 that no case saw would have said 5 / 9 = 55.6 %.
TEST(MutationScore, EquivalentIsEarnedOnThreeSmallNetworks) {
  const ToolResult r = mutate("score_three",
                              "ORG X0\nAND X1\nOUT Y0\n"
                              "ORG X2\nOR X3\nOUT Y1\nOUT Y1\nOUT Y3\n"
                              "ORG X4\nOR X4\nOUT Y2\nEND\n",
                              "cases:\n  - name: the AND\n    steps:\n"
                              "      - at: 100ms\n        set: {X0: on, X1: on}\n"
                              "      - after: 10ms\n        expect: Y0\n");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, ": 20 mutants, 1 case each\n  killed 5, survived 10 (not executed 0, not observed 6, "
                         "not checked 4), equivalent-suspect 5, not loaded 0: score 33.3 %\n")) << r.out;
  EXPECT_FALSE(has(r.out, "55.6 %")) << r.out;
  EXPECT_TRUE(has(r.out, "  network 1 (line 1): 5/6 killed\n  network 2 (line 4): 0/6 killed, 2 equivalent-suspect\n"
                         "  network 3 (line 9): 0/3 killed, 3 equivalent-suspect\n")) << r.out;
  // The lines docs/testing-your-cell.md shows.
  EXPECT_TRUE(has(r.out, "cell.il:2: AND X1 \u2192 OR X1 in network 1 (line 1): survived: executed (by every case), "
                         "but no case sees a difference; an input search tells it apart: Y0 ON, the original's OFF at "
                         "0.002 s of the exhaustive run over X0, X1 (one scan a step)\n")) << r.out;
  EXPECT_TRUE(has(r.out, "cell.il:4: ORG X2 \u2192 ORG NOT X2 in network 2 (line 4): survived: no case checks it "
                         "(executed by every case)\n")) << r.out;
  EXPECT_TRUE(has(r.out, "cell.il:10: OR X4 \u2192 AND X4 in network 3 (line 9): equivalent-suspect: no case and no "
                         "input search tells it apart (every combination of X4 (one scan a step, then 1.000 s), then "
                         "10 exploration runs of 10.000 s (inputs X0, X1, X2, X3, X4, seed 1))\n")) << r.out;
}

// Three cases test the first half of the program (a start/stop latch, a lamp, a delayed
// output, an alarm and a constant); the second half, a routine called while X7 is ON, no
// case reaches.
//
//   network 1 (line 1)   ORG X0 / OR Y0 / AND NOT X1 / OUT Y0   8 mutants, 7 killed: ORG TU X0
//                        latches as ORG X0 does unless X0 is held while X1 is released
//                        (no case sees it: not observed)
//   network 2 (line 5)   ORG Y0 / AND X2 / OUT Y1 / OUT Y7      7 mutants, 7 killed
//   network 3 (line 9)   ORG Y0 / TMR T0 10                     6 mutants, 5 killed: T0 11 turns
//                        Y2 on 10 ms later, inside the 12 ms the case allows (not checked)
//   network 4 (line 11)  ORG T0 / OUT Y2                        3 mutants, 2 killed: ORG TU T0
//                        gives Y2 for one scan, no case looks after it (not observed)
//   network 5 (line 13)  ORG X3 / AND NOT Y0 / OUT Y3           5 mutants, 5 killed
//   network 6 (line 16)  ORG M1925 / FUN 8 MOV S=5 D=R10        4 mutants, 3 killed: ORG TU
//                        M1925 writes the same 5 once: equivalent-suspect
//   network 7 (line 18)  ORG X7 / CALL SERVICE                  2 mutants, executed, not observed
//   networks 8-10 (lines 22-31) the routine: 6 + 5 + 9 mutants, no case executes them
//
// Killed 29. Survivors: 20 not executed, 4 not observed (ORG TU X0, ORG TU T0 and the two
// of ORG X7), 1 not checked (T0 11); 1 equivalent-suspect. 29 / (29 + 25) = 53.7 %.
// Leaving out every mutant no case saw would have said 29 / 30 = 96.7 %.
TEST(MutationScore, ASuiteThatNeverReachesHalfTheProgram) {
  const ToolResult r = mutate(
      "score_half",
      "ORG X0\nOR Y0\nAND NOT X1\nOUT Y0\n"
      "ORG Y0\nAND X2\nOUT Y1\nOUT Y7\n"
      "ORG Y0\nTMR T0 10\n"
      "ORG T0\nOUT Y2\n"
      "ORG X3\nAND NOT Y0\nOUT Y3\n"
      "ORG M1925\nFUN 8 MOV S=5 D=R10\n"
      "ORG X7\nCALL SERVICE\nEND\n"
      "LBL SERVICE\n"
      "ORG X4\nAND X5\nOUT Y4\n"
      "ORG X5\nAND NOT X6\nOUT Y5\n"
      "ORG X4\nOR X6\nAND X5\nOUT Y6\nRTS\n",
      "cases:\n"
      "  - name: start, run, stop\n    steps:\n"
      "      - expect: not Y0 and not Y2\n        stays: 99ms\n"
      "      - at: 100ms\n        set: {X0: on}\n"
      "      - expect: Y0\n        within: 1ms\n"
      "      - set: {X0: off}\n"
      "      - expect: Y0 and not Y2\n        stays: 98ms\n"
      "      - expect: Y2\n        within: 12ms\n"
      "      - set: {X1: on}\n"
      "      - expect: not Y0 and not Y2\n        within: 1ms\n"
      "  - name: the lamp\n    steps:\n"
      "      - at: 10ms\n        set: {X2: on}\n"
      "      - expect: not Y1\n        stays: 50ms\n"
      "      - set: {X0: on}\n"
      "      - expect: Y1 and Y7\n        within: 1ms\n"
      "      - expect: Y1 and Y7\n        stays: 10ms\n"
      "      - set: {X2: off}\n"
      "      - expect: not Y1 and not Y7 and R10 == 5\n        within: 1ms\n"
      "  - name: the alarm\n    steps:\n"
      "      - at: 10ms\n        set: {X3: on}\n"
      "      - expect: Y3\n        within: 1ms\n"
      "      - expect: Y3\n        stays: 10ms\n"
      "      - set: {X0: on}\n"
      "      - expect: not Y3\n        within: 2ms\n");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, ": 55 mutants, 3 cases each\n  killed 29, survived 25 (not executed 20, not observed 4, "
                         "not checked 1), equivalent-suspect 1, not loaded 0: score 53.7 %\n")) << r.out;
  EXPECT_FALSE(has(r.out, "96.7 %")) << r.out;
  EXPECT_TRUE(has(r.out, "  network 7 (line 18): 0/2 killed\n  network 8 (line 22): 0/6 killed\n"
                         "  network 9 (line 25): 0/5 killed\n  network 10 (line 28): 0/9 killed\n")) << r.out;
  EXPECT_TRUE(has(r.out, "cell.il:23: AND X5 \u2192 OR X5 in network 8 (line 22): survived: no case executes it; an "
                         "input search tells it apart: ")) << r.out;
  EXPECT_TRUE(has(r.out, "cell.il:10: TMR T0 10 \u2192 TMR T0 11 in network 3 (line 9): survived: no case checks it "
                         "(executed by every case)\n")) << r.out;
}

// A suite whose mutants are all equivalent-suspects (the ADC example copies a channel that
// no case reads, and the search drives no analog input) killed nothing of nothing: no score,
// not 100 %.
TEST(MutationScore, NothingCountedIsNoScore) {
  const std::string json = ::testing::TempDir() + "/score_none.json";
  const ToolResult r = run_tool("test " + std::string(PLC_CELL_SOURCE_DIR) +
                                "/examples/temp/adc_conditioning.scenario.yaml --mutate --mutate-json " + json);
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, "  killed 0, survived 0 (not executed 0, not observed 0, not checked 0), equivalent-suspect 2, "
                         "not loaded 0: no score (no mutant counts)\n")) << r.out;
  EXPECT_FALSE(has(r.out, "100.0 %")) << r.out;
  EXPECT_TRUE(has(plc_cell::testing::slurp(json), "\"not_loaded\": 0, \"score\": null,")) << plc_cell::testing::slurp(json);
}
