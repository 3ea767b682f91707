// examples/oven run through the plc_cell tool as a user would (built by catkin only:
// it needs PLC_CELL_TOOL and PLC_CELL_SOURCE_DIR).
#include <gtest/gtest.h>

#include <string>

#include "../harness/child_process.h"

namespace {

std::string run(const std::string& args, int* status) {
  const auto r = plc_cell::testing::run_shell(std::string(PLC_CELL_TOOL) + " " + args);
  *status = r.status;
  return r.out;
}

TEST(OvenExample, SimHoldsTheSetPoint) {
  int status = -1;
  const std::string out = run(std::string("sim --config ") + PLC_CELL_SOURCE_DIR +
                                  "/examples/oven/oven.yaml --duration 1800s --scan 10ms "
                                  "--watch R0,in_zone,pid_error,pid_alarm,R5000:hex",
                              &status);
  EXPECT_EQ(status, 0) << out;
  EXPECT_NE(out.find("180000 scans of 10000 us"), std::string::npos) << out;
  const size_t at = out.find("R0 = ");
  ASSERT_NE(at, std::string::npos) << out;
  const int r0 = std::stoi(out.substr(at + 5));
  EXPECT_NEAR(r0, 2000, 10) << out;  // 200.0 degC within 1 degC
  EXPECT_NE(out.find("in_zone = 1"), std::string::npos) << out;
  EXPECT_NE(out.find("pid_error = 0"), std::string::npos) << out;
  EXPECT_NE(out.find("pid_alarm = 0"), std::string::npos) << out;
  EXPECT_NE(out.find("R5000:hex = 0xA556"), std::string::npos) << out;  // the table is valid
}

TEST(OvenExample, CheckKnowsTheTemperatureFunctions) {
  int status = -1;
  const std::string out =
      run(std::string("check --program ") + PLC_CELL_SOURCE_DIR + "/examples/oven/oven.il", &status);
  EXPECT_EQ(status, 0) << out;
}

}  // namespace
