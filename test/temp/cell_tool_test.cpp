// The RTC, an expansion board, FUN33 and FUN139/PWMDA in one cell, run through the
// plc_cell tool as a user would (virtual time: deterministic with modules.rtc.start).
#include <gtest/gtest.h>

#include <stdlib.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../core/run_tool.h"

namespace plc_cell {
namespace {

const char* kYaml = R"(cell:
  name: rtc
  program: cell.il
modules:
  rtc: {start: 2026-01-01T23:59:58}
  pwmda:
    - {output: Y0, trim: hardware}
  analog:
    board:
      type: B2A1D
      inputs: [{value: 5}]
      outputs: [{current: true}]
)";

// D4072 (5 V: 8192) through FUN33's 4-20 mA table into the board's output D4076.
const char* kProgram =
    "ORG M1925\n"
    "MOV S=0 D=R1000\nMOV S=16383 D=R1001\nMOV S=3276 D=R1002\nMOV S=16383 D=R1003\n"
    "MOV S=D4072 D=R0\n"
    "FUN 33 S=R0 Ts=R1000 D=D4076 N=1\n"
    "FUN 139 Pw=0 Op=0 Rs=1 Pn=1 OR=R10 WR=R100\n"
    "END\n";

TEST(CellTool, RtcBoardAndAnalogFunctionsInSim) {
  char dir[] = "/tmp/plc_cell_rtc_XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  const std::string d = dir;
  std::ofstream(d + "/cell.yaml") << kYaml;
  std::ofstream(d + "/cell.il") << kProgram;
  const auto r = testing::run_tool("sim --config " + d + "/cell.yaml --duration 3s --scan 10ms "
                                   "--watch R4128,R4129,R4130,R4131,R4133,R4134,D4072,D4076,M1954");
  EXPECT_EQ(r.status, 0) << r.out;
  // 23:59:58 + 2.99 s (the last scan) = 00:00:00 on Friday 2 January 2026.
  for (const char* line : {"R4128 = 0\n", "R4129 = 0\n", "R4130 = 0\n", "R4131 = 2\n", "R4133 = 26\n",
                           "R4134 = 5\n", "D4072 = 8192\n", "D4076 = 9830\n", "M1954 = 1\n"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << r.out;
  const auto check = testing::run_tool("check --program " + d + "/cell.il");
  EXPECT_EQ(check.status, 0) << check.out;
  testing::run_shell("rm -r " + d);
}

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Every virtual-time entry point gives the same bytes whenever it runs: the RTC of a cell
// without modules.rtc.start starts at 2024-01-01T00:00:00 (docs/analog-and-temperature.md),
// not at the host's time. A program that copies the clock into its outputs shows it.
TEST(CellTool, VirtualTimeRunsAreTheSameWheneverTheyAreMade) {
  char dir[] = "/tmp/plc_cell_clock_XXXXXX";
  ASSERT_NE(mkdtemp(dir), nullptr);
  const std::string d = dir;
  std::ofstream(d + "/cell.yaml") << "cell: {name: clock, program: cell.il}\nsignals: {go: X0, lamp: Y0}\n";
  std::ofstream(d + "/cell.il") << "ORG M1925\nMOV S=R4128 D=R0\nMOV S=R4135 D=R1\nORG X0\nOUT Y0\nEND\n";
  std::ofstream(d + "/s.scenario.yaml")
      << "cell: cell.yaml\nproperties:\n  - never: lamp and not go\n"
         "explore:\n  inputs: {go: {hold: [10ms, 100ms]}}\n  run: 1s\n  budget: 2s\n"
         "cases:\n  - name: lamp\n    steps:\n      - set: {go: on}\n      - expect: lamp\n        within: 10ms\n"
         "      - at: 1s\n        expect: R0 == 1\n";
  std::vector<std::string> outputs;
  for (const char* run : {"1", "2"}) {
    const std::string r = d + "/" + run;
    testing::run_shell("mkdir -p " + r);
    const auto sim = testing::run_tool("sim --config " + d + "/cell.yaml --duration 2s --watch R0,R1 --trace " + r +
                                       "/trace.csv --record " + r + "/sim.plcrec");
    EXPECT_EQ(sim.status, 0) << sim.out;
    const auto test = testing::run_tool("test " + d + "/s.scenario.yaml --record " + r + "/cases");
    EXPECT_EQ(test.status, 0) << test.out;
    const auto explore = testing::run_tool("explore " + d + "/s.scenario.yaml --out " + r + "/found.yaml");
    EXPECT_EQ(explore.status, 0) << explore.out;
    outputs.push_back(sim.out + test.out + explore.out + file_text(r + "/trace.csv") + file_text(r + "/sim.plcrec") +
                      file_text(r + "/cases/lamp.plcrec"));
  }
  EXPECT_EQ(outputs[0], outputs[1]);
  // At the first scan (t = 0) the program copied 0 s and 00:00 of the documented instant.
  const std::string trace = file_text(d + "/1/trace.csv");
  EXPECT_NE(trace.find("0.000000,R0,0\n0.000000,R1,0\n"), std::string::npos) << trace;
  EXPECT_NE(trace.find("1.000000,R0,1\n"), std::string::npos) << trace;
  testing::run_shell("rm -r " + d);
}

}  // namespace
}  // namespace plc_cell
