// `plc_cell test --record DIR`: one file per case, named after it; a failing case's file
// carries the failing check's instant and text and opens there with the values the check saw,
// and the tool prints the command that opens it in the monitor at the failure.
#include <gtest/gtest.h>

#include "helpers.h"
#include "plc_cell/recording/replay_source.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {
namespace {

const std::string& kFails = testing::kFailingScenario;

TEST(RecordedCase, AFailingCaseOpensAtItsFailure) {
  const std::string dir = testing::scratch_dir("cases");
  const auto r = testing::run_tool("test " + kFails + " --record " + dir);
  EXPECT_EQ(r.status, 1) << r.out;  // one case fails on purpose
  const std::string failing = dir + "/the_stopper_lowers_1_s_after_the_part_arrives.plcrec";
  const std::string passing = dir + "/the_belt_runs.plcrec";
  // The exact command, once, under the failing case only.
  const std::string command = "plc_cell monitor --recording " + failing + " --open-at failure";
  EXPECT_NE(r.out.find("    recorded: " + command + "\n"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("recorded: plc_cell monitor --recording " + passing), std::string::npos) << r.out;

  const recording::Reader ok = recording::Reader::load(passing);
  EXPECT_FALSE(ok.info().failure_us);
  EXPECT_EQ(ok.info().source, "plc_cell test " + kFails + ": the belt runs");

  recording::ReplaySource src(recording::Reader::load(failing), failing, SoftCell::functions());
  ASSERT_TRUE(src.failure_us());
  // The part arrives at 1 s (pick_request); the check gives the stopper 1 s more.
  EXPECT_GE(*src.failure_us(), 2000000u);
  EXPECT_LE(*src.failure_us(), 2011000u);
  EXPECT_EQ(src.end_us(), *src.failure_us());  // the case ends at its failure
  const std::string& text = src.reader().info().failure;
  EXPECT_NE(text.find("stopper_lower"), std::string::npos) << text;
  EXPECT_NE(r.out.find(text), std::string::npos) << "the report's failure line is the recorded one";

  src.seek(*src.failure_us());
  EXPECT_EQ(src.cursor_us(), *src.failure_us());
  // What the check saw: the robot still called (Y2), the stopper not lowered (Y1).
  const monitor::Frame f = src.read({parse_address("Y2"), parse_address("Y1")});
  EXPECT_EQ(f.values, (std::vector<uint32_t>{1, 0}));
  // And the same values as a fresh run of the cell at that instant.
  testing::ConveyorRun fresh;
  recording::Image expected = fresh.image_after(*src.failure_us()), got;
  src.reader().image_after(src.reader().scan_at(*src.failure_us()), &got);
  EXPECT_TRUE(expected.bits == got.bits);
  EXPECT_TRUE(expected.words == got.words);
}

TEST(RecordedCase, AFolderThatCannotBeMadeIsAnError) {
  const auto r = testing::run_tool("test " + kFails + " -k 'belt runs' --record /proc/no_such_dir");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("cannot make the recording folder /proc/no_such_dir"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace plc_cell
