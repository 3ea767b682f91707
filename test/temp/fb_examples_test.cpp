// examples/temp run through the plc_cell tool as a user would: the FB oven (FUN85 and the
// FB FUN86) and the FB manual's FUN73 example 1; `check` without the cell's config
// rejects the FB instructions, with it accepts them.
#include <gtest/gtest.h>

#include <string>

#include "../core/run_tool.h"

namespace plc_cell {
namespace {

const std::string kDir = std::string(PLC_CELL_SOURCE_DIR) + "/examples/temp/";

int value(const std::string& out, const std::string& name) {
  const size_t at = out.find("\n" + name + " = ");
  return at == std::string::npos ? -99999 : std::stoi(out.substr(at + name.size() + 4));
}

TEST(FbExamples, OvenHolds200WithFun85AndFbFun86) {
  const auto r = testing::run_tool("sim --config " + kDir + "fb_oven.yaml --duration 1800s --scan 10ms "
                                   "--watch R0,R1,R2,in_zone,pid_alarm,pid_error,line_broken");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NEAR(value(r.out, "R0"), 200, 1) << r.out;  // degC, the FB's 1 degree
  EXPECT_EQ(value(r.out, "R1"), 22) << r.out;
  EXPECT_EQ(value(r.out, "R2"), 0) << r.out;  // not installed (R4010 = 3): 0, no line-broken check
  EXPECT_EQ(value(r.out, "in_zone"), 1) << r.out;
  EXPECT_EQ(value(r.out, "pid_alarm"), 0) << r.out;
  EXPECT_EQ(value(r.out, "pid_error"), 0) << r.out;
  EXPECT_EQ(value(r.out, "line_broken"), 0) << r.out;
}

TEST(FbExamples, Fun73Example1HoldsZone1) {
  const auto r = testing::run_tool("sim --config " + kDir + "fun73_example1.yaml --duration 1800s --scan 10ms "
                                   "--watch R0,R1,zone1_in,warnings,line_broken,M10");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NEAR(value(r.out, "R0"), 200, 1) << r.out;
  EXPECT_EQ(value(r.out, "R1"), 23) << r.out;
  EXPECT_EQ(value(r.out, "zone1_in"), 1) << r.out;
  EXPECT_EQ(value(r.out, "warnings"), 0) << r.out;
  EXPECT_EQ(value(r.out, "M10"), 0) << r.out;
}

TEST(FbExamples, CheckNeedsTheCellsGeneration) {
  const auto fbs = testing::run_tool("check --program " + kDir + "fb_oven.il");
  EXPECT_EQ(fbs.status, 1);
  EXPECT_NE(fbs.out.find("fb_oven.il:12:5: error: FUN 85 TPSNS: belongs to the FB generation"), std::string::npos)
      << fbs.out;
  const auto fb = testing::run_tool("check --program " + kDir + "fb_oven.il --config " + kDir + "fb_oven.yaml");
  EXPECT_EQ(fb.status, 0) << fb.out;
}

}  // namespace
}  // namespace plc_cell
