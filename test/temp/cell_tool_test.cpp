// The RTC, an expansion board, FUN33 and FUN139/PWMDA in one cell, run through the
// plc_cell tool as a user would (virtual time: deterministic with modules.rtc.start).
#include <gtest/gtest.h>

#include <stdlib.h>

#include <fstream>
#include <string>

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

}  // namespace
}  // namespace plc_cell
