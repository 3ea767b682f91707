// The tool with a line (docs/lines.md): `plc_cell sim --line`, `plc_cell test` of a file that
// names a line (with --coverage, --record, --junit and --mutate), `plc_cell explore` of one,
// and the example line's scenario, exploration and broken variant, run as a user runs them.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <vector>

#include "../core/run_tool.h"
#include "../core/tool_text.h"
#include "line_fixture.h"
#include "plc_cell/recording/line_recording.h"

namespace plc_cell {
namespace testing {
namespace {

const std::string kExample = std::string(PLC_CELL_SOURCE_DIR) + "/examples/line/";

TEST(LineCli, TheExampleLinesScenarioPasses) {
  const ToolResult r = run_tool("test " + kExample + "line.scenario.yaml");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, "== 7 passed, 0 failed")) << r.out;
}

TEST(LineCli, TheExampleLineRunsTheSameEveryTime) {
  // 60 s: parts enter at 1, 7, ..., 55 s (10 in); the k-th part's test ends at
  // 6.842 + 6k s and passes when (that - 0.5 s) mod 10 s < 7 s: 8.342 s fails (k = 2, 7),
  // the tenth part is still on the table. 7 passed, 2 rejected, 1 on the table.
  const std::string dir = ::testing::TempDir();
  std::string outs[2];
  for (int i = 0; i < 2; ++i) {
    const std::string n = std::to_string(i);
    const ToolResult r = run_tool("sim --line " + kExample + "line.line.yaml --duration 60s --watch "
                                  "infeed.R0,test.R1,test.R3,test.R2,robot.in_zone --trace " + dir + "/lt" + n +
                                  ".csv --record " + dir + "/lr" + n + ".plcrec");
    ASSERT_EQ(r.status, 0) << r.out;
    outs[i] = r.out;
  }
  EXPECT_EQ(outs[0],
            "# plc_cell sim: line example_line, 3 cells, 60000 instants of 1000 us, virtual time 60.000000 s\n"
            "#   infeed: 60000 scans of 1000 us, RUN\n"
            "#   robot: 60000 scans of 1000 us, RUN\n"
            "#   test: 30000 scans of 2000 us, RUN\n"
            "infeed.R0 = 10\ntest.R1 = 7\ntest.R3 = 2\ntest.R2 = 1\nrobot.in_zone = 0\n");
  EXPECT_EQ(outs[1], outs[0]);
  EXPECT_EQ(slurp(dir + "/lt0.csv"), slurp(dir + "/lt1.csv"));
  EXPECT_EQ(slurp(dir + "/lr0.plcrec"), slurp(dir + "/lr1.plcrec"));
  // Without a trace, the same run to the byte of its recording.
  const ToolResult windows = run_tool("sim --line " + kExample + "line.line.yaml --duration 60s --watch "
                                      "infeed.R0,test.R1,test.R3,test.R2,robot.in_zone --record " + dir + "/lr2.plcrec");
  ASSERT_EQ(windows.status, 0) << windows.out;
  EXPECT_EQ(windows.out, outs[0]);
  EXPECT_EQ(slurp(dir + "/lr2.plcrec"), slurp(dir + "/lr0.plcrec"));
  // The robot enters the zone at 3.54 s with the first part (docs/lines.md walks through it).
  EXPECT_TRUE(has(slurp(dir + "/lt0.csv"), "\n3.540000,robot.in_zone,1\n"));
  const auto rec = recording::LineReader::load(dir + "/lr0.plcrec");
  ASSERT_EQ(rec.size(), 3u);
  EXPECT_EQ(rec.info().line, "example_line");
  EXPECT_EQ(rec.name(2), "test");
  EXPECT_EQ(rec.cell(0).scans(), 60000u);
  EXPECT_EQ(rec.cell(2).scans(), 30000u);
  EXPECT_EQ(rec.info().wires.at(3), "infeed.release -> robot.nest_sensor (a part: travel 1.500 s, length 0.200 s)");
}

// The rows of a trace after its header, each as (instant, cell's place in cells), in order;
// every row's name is CELL.NAME of one of cells.
std::vector<std::pair<double, size_t>> trace_rows(const std::string& csv, const std::vector<std::string>& cells) {
  std::istringstream rows(csv);
  std::string row;
  std::getline(rows, row);
  std::vector<std::pair<double, size_t>> out;
  while (std::getline(rows, row)) {
    const size_t c1 = row.find(','), c2 = row.find(',', c1 + 1);
    const std::string name = row.substr(c1 + 1, c2 - c1 - 1);
    const auto cell = std::find(cells.begin(), cells.end(), name.substr(0, name.find('.')));
    EXPECT_NE(cell, cells.end()) << row;
    out.push_back({std::stod(row.substr(0, c1)), size_t(cell - cells.begin())});
  }
  return out;
}

TEST(LineCli, ATraceComesInTheOrderOfTheInstantsAndOfTheCells) {
  // b and c follow a (no wire back): the line runs each a whole window ahead of the next, yet
  // the trace lists each instant's rows in the file's order of the cells, c before a.
  LineFolder f("trace_order", {{"blink.il", "ORG NOT M1\nTMR T0 2\nORG T0\nOUT M1\nORG M1\nFUN 9 MOVN S=WY0 D=WY0\nEND\n"},
                               {"copy.il", "ORG X20\nOUT Y0\nEND\n"},
                               {"a.yaml", cell_yaml("a", "blink.il")},
                               {"b.yaml", cell_yaml("b", "copy.il")},
                               {"c.yaml", cell_yaml("c", "copy.il", "0.002")},
                               {"l.line.yaml", "cells:\n  c: c.yaml\n  a: a.yaml\n  b: b.yaml\nwires:\n"
                                               "  - {from: a.Y0, to: b.X20}\n  - {from: b.Y0, to: c.X20, delay: 3ms}\n"}});
  const ToolResult r = run_tool("sim --line " + f.path("l.line.yaml") + " --duration 20s --watch a.Y0,a.M1,b.Y0,c.Y0 "
                                "--trace " + f.path("t.csv"));
  ASSERT_EQ(r.status, 0) << r.out;
  const auto rows = trace_rows(slurp(f.path("t.csv")), {"c", "a", "b"});
  // a's timer (20 ms, then a scan to restart) inverts Y0 with a one-scan pulse of M1: some
  // 900 times in 20 s, each with a row for M1 on, M1 off, a's Y0, b's Y0 and c's Y0.
  ASSERT_GT(rows.size(), 4000u);
  for (size_t i = 1; i < rows.size(); ++i) ASSERT_LE(rows[i - 1], rows[i]) << "row " << i + 1 << " of the trace";
  // M1 goes off at the instant b's Y0 follows a's (the zero-delay wire: b's next scan): those
  // instants hold a row of a before a row of b.
  size_t shared = 0;
  for (size_t i = 1; i < rows.size(); ++i) shared += rows[i - 1].first == rows[i].first && rows[i - 1].second != rows[i].second;
  EXPECT_GT(shared, 800u);
}

TEST(LineCli, ExploringTheExampleFindsNothing) {
  const ToolResult r = run_tool("explore " + kExample + "line.scenario.yaml");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, "no property violated")) << r.out;
}

TEST(LineCli, ExploringTheBrokenVariantFindsTheRobotAndTheHandlerInTheZoneAndWritesACase) {
  const std::string out = ::testing::TempDir() + "/broken_line_case.scenario.yaml";
  std::remove(out.c_str());
  const ToolResult r = run_tool("explore " + kExample + "broken.explore.yaml --out " + out);
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(has(r.out, "broken.explore.yaml:8: property never: robot.in_zone and test.handler_in_zone violated"))
      << r.out;
  EXPECT_TRUE(has(r.out, "wrote " + out)) << r.out;
  const std::string file = slurp(out);
  EXPECT_TRUE(has(file, "line: ")) << file;
  // The case reproduces the violation, on its own.
  const ToolResult again = run_tool("test " + out);
  EXPECT_EQ(again.status, 1) << again.out;
  EXPECT_TRUE(has(again.out, "property never: robot.in_zone and test.handler_in_zone violated")) << again.out;
  EXPECT_TRUE(has(again.out, "== 0 passed, 1 failed")) << again.out;
}

TEST(LineCli, CoverageIsPerProgramAndJunitAndRecordingsAsForACell) {
  const std::string dir = ::testing::TempDir() + "/line_cli_rec";
  std::system(("rm -rf " + dir).c_str());
  const ToolResult r = run_tool("test " + kExample + "line.scenario.yaml -k 'a part goes' --coverage --junit " +
                                dir + ".xml --record " + dir);
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* p : {"infeed.il", "robot.il", "test_station.il"})
    EXPECT_TRUE(has(r.out, std::string("coverage of ") + kExample + p + " (1 run)")) << p << "\n" << r.out;
  const std::string junit = slurp(dir + ".xml");
  EXPECT_TRUE(has(junit, "<testcase classname=\"line.scenario\" name=\"a part goes from the infeed through the robot to "
                         "the test station\" file=\"" + kExample + "line.scenario.yaml\" line=\"29\" time=\"4.342000\"/>"))
      << junit;
  // The case ends at 4.342 s: 4343 scans of the 1 ms cells, 2172 of the 2 ms station.
  const auto rec = recording::LineReader::load(dir + "/a_part_goes_from_the_infeed_through_the_robot_to_the_test_station.plcrec");
  ASSERT_EQ(rec.size(), 3u);
  EXPECT_EQ(rec.cell(0).scans(), 4343u);
  EXPECT_EQ(rec.cell(1).scans(), 4343u);
  EXPECT_EQ(rec.cell(2).scans(), 2172u);
  EXPECT_EQ(rec.info().source, "plc_cell test " + kExample + "line.scenario.yaml: a part goes from the infeed through "
                               "the robot to the test station");
}

TEST(LineCli, MutationTestingMutatesEachProgramOfTheLineAgainstItsCases) {
  // a and b both run copy.il (Y0 = X20), a.Y0 wired to b.X20, and a mutant runs in both.
  // The case holds b.Y0 ON for 50 ms: the rising edge (b.Y0 ON for one scan) and the deleted
  // coil fail it; the inverted contact inverts twice, a's output and b's, and b.Y0 is ON as
  // before: it survives, seen by no case (a.Y0 differs, which no case reads). other.il (c)
  // has three mutants, each of which turns c.Y1 OFF when the case expects it ON with b.Y0.
  LineFolder f("mutate", {{"copy.il", "ORG X20\nOUT Y0\nEND\n"},
                          {"other.il", "ORG M1925\nOUT Y1\nEND\n"},
                          {"a.yaml", cell_yaml("a", "copy.il")},
                          {"b.yaml", cell_yaml("b", "copy.il")},
                          {"c.yaml", cell_yaml("c", "other.il")},
                          {"l.line.yaml", "cells: {a: a.yaml, b: b.yaml, c: c.yaml}\nwires:\n  - {from: a.Y0, to: b.X20}\n"},
                          {"s.scenario.yaml", "line: l.line.yaml\ncases:\n  - name: b follows a\n    steps:\n"
                                              "      - set: {a.X20: on}\n      - expect: b.Y0 and c.Y1\n        within: 5ms\n"
                                              "      - expect: b.Y0\n        stays: 50ms\n"}});
  const ToolResult r = run_tool("test " + f.path("s.scenario.yaml") + " --mutate");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, "mutation testing of " + f.path("copy.il") + ": 3 mutants, 1 case each\n"
                         "  killed 2, survived 1 (not executed 0, not observed 0, not checked 1)")) << r.out;
  EXPECT_TRUE(has(r.out, f.path("copy.il") + ":1: ORG X20 → ORG NOT X20 in network 1 (line 1): survived: no case "
                         "checks it")) << r.out;
  EXPECT_TRUE(has(r.out, "mutation testing of " + f.path("other.il") + ": 3 mutants, 1 case each\n  killed 3, survived 0"))
      << r.out;
}

TEST(LineCli, AScenarioFilesNamesAreCheckedAgainstTheLineBeforeAnyCaseRuns) {
  LineFolder f("names", {{"copy.il", "ORG X20\nOUT Y0\nEND\n"},
                         {"a.yaml", cell_yaml("a", "copy.il")},
                         {"l.line.yaml", "cells: {a: a.yaml}\n"},
                         {"s.scenario.yaml", "line: l.line.yaml\n"
                                             "properties:\n  - never: z.Y0\n"
                                             "cases:\n  - name: c\n    steps:\n"
                                             "      - set: {a.X20: on}\n"
                                             "      - expect: Y0\n"
                                             "      - expect: a.nothing\n"},
                         {"both.scenario.yaml", "line: l.line.yaml\ncell: a.yaml\ncases: []\n"}});
  const ToolResult r = run_tool("test " + f.path("s.scenario.yaml"));
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(has(r.out, f.path("s.scenario.yaml") + ":3: error: key 'never': 'z.Y0': no cell 'z' in the line (a)"))
      << r.out;
  EXPECT_TRUE(has(r.out, f.path("s.scenario.yaml") + ":8:17: error: key 'cases[0].steps[1].expect': 'Y0': a line's "
                         "names start with their cell: CELL.Y0\n")) << r.out;
  EXPECT_TRUE(has(r.out, f.path("s.scenario.yaml") + ":9: error: key 'expect': a: 'nothing' is neither a signal of "
                         "cell a nor an address")) << r.out;
  EXPECT_TRUE(has(r.out, "plc_cell test: 3 error(s) in the scenario files; no case ran")) << r.out;
  const ToolResult both = run_tool("test " + f.path("both.scenario.yaml"));
  EXPECT_TRUE(has(both.out, f.path("both.scenario.yaml") + ":2:7: error: key 'cell': a scenario runs a cell or a "
                            "line, not both: 'line' is given")) << both.out;
}

TEST(LineCli, SimOfALineRefusesACellsOptionsAndUnknownNames) {
  const std::string line = kExample + "line.line.yaml";
  ToolResult r = run_tool("sim --line " + line + " --duration 1s --config x.yaml");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_TRUE(has(r.out, "--config goes with a cell, not --line")) << r.out;
  r = run_tool("sim --line " + line + " --duration 1s --watch robbot.in_zone");
  EXPECT_TRUE(has(r.out, "--watch robbot.in_zone: no cell 'robbot' in the line (infeed, robot, test)")) << r.out;
  r = run_tool("sim --line " + line + " --duration 1s --set R0=5");
  EXPECT_TRUE(has(r.out, "--set R0=5: a line's names are CELL.NAME (cells: infeed, robot, test)")) << r.out;
  r = run_tool("sim --line " + line + " --duration 10ms --set infeed.R0=5 --watch infeed.R0");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, "infeed.R0 = 5\n")) << r.out;
}

TEST(LineCli, TheMonitorOpensALinesRecordingOrOneOfItsCells) {
  const std::string dir = ::testing::TempDir();
  ASSERT_EQ(run_tool("sim --line " + kExample + "line.line.yaml --duration 10ms --record " + dir + "/m.plcrec").status, 0);
  // Without --cell: every cell, with the overview (docs/monitor.md).
  ToolResult r = run_tool("monitor --recording " + dir + "/m.plcrec --duration 1ms --http-tcp 127.0.0.1:0");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, "for line example_line (recording " + dir + "/m.plcrec): cells infeed, robot, test")) << r.out;
  r = run_tool("monitor --recording " + dir + "/m.plcrec --cell robbot --duration 1ms --http-tcp 127.0.0.1:0");
  EXPECT_TRUE(has(r.out, "--cell robbot: line example_line has no such cell (infeed, robot, test)")) << r.out;
  r = run_tool("monitor --recording " + dir + "/m.plcrec --cell robot --duration 1ms --http-tcp 127.0.0.1:0");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, "for recording " + dir + "/m.plcrec (cell robot)")) << r.out;
}

TEST(LineCli, RunServesOneMonitorForTheLinesCells) {
  ToolResult r = run_tool("run --line " + kExample + "line.line.yaml --duration 300ms --http-tcp 127.0.0.1:0");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, "plc_cell run: serving monitor http://127.0.0.1:")) << r.out;
  EXPECT_TRUE(has(r.out, " for line example_line (infeed, robot, test)")) << r.out;
  // What goes with one cell is refused, naming the option, and nothing runs.
  r = run_tool("run --line " + kExample + "line.line.yaml --config x.yaml --duration 1ms");
  EXPECT_NE(r.status, 0);
  EXPECT_TRUE(has(r.out, "--config goes with a cell, not --line")) << r.out;
  r = run_tool("run --line " + kExample + "line.line.yaml --fatek-tcp 127.0.0.1:0 --duration 1ms");
  EXPECT_NE(r.status, 0);
  EXPECT_TRUE(has(r.out, "--http-* serves the line's monitor")) << r.out;
}

}  // namespace
}  // namespace testing
}  // namespace plc_cell
