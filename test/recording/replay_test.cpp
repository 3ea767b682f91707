// A recorded run as the monitor's source: the cursor's moves (seek, by scan, by event),
// clamped to the run, the values at the cursor, and every change refused.
#include <gtest/gtest.h>

#include "helpers.h"
#include "plc_cell/recording/replay_source.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {
namespace {

class Replay : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    path_ = new std::string(testing::record_conveyor(testing::scratch_dir("replay"), "3s"));
  }
  static void TearDownTestSuite() { delete path_; }
  recording::ReplaySource source{recording::Reader::load(*path_), "run.plcrec", SoftCell::functions()};
  const Address y0 = parse_address("Y0"), y2 = parse_address("Y2"), r0 = parse_address("R0");
  static std::string* path_;
};
std::string* Replay::path_ = nullptr;

TEST_F(Replay, TheRunsBoundsAndTheProgram) {
  EXPECT_EQ(source.begin_us(), 0u);
  EXPECT_EQ(source.end_us(), 2999000u);
  EXPECT_EQ(source.cursor_us(), 0u);
  EXPECT_EQ(source.scans(), 3000u);
  EXPECT_FALSE(source.failure_us());
  EXPECT_EQ(source.replay(), &source);
  EXPECT_EQ(source.describe(), "recording run.plcrec");
  ASSERT_TRUE(source.program());
  EXPECT_EQ(source.program()->file, "conveyor.il");
  EXPECT_FALSE(source.program()->program.code.empty());
}

TEST_F(Replay, SeekGoesToTheLastScanAtOrBeforeAndClamps) {
  source.seek(1000500);
  EXPECT_EQ(source.cursor_us(), 1000000u);
  monitor::Frame f = source.read({y0, y2});
  EXPECT_EQ(f.scan, 1001u);
  EXPECT_EQ(f.t_us, 1000000u);
  EXPECT_EQ(f.mode, RunMode::Run);
  // The part reaches the stopper at 1 s: the robot is called and the belt stops.
  EXPECT_EQ(f.values, (std::vector<uint32_t>{0, 1}));
  source.seek(999000);
  EXPECT_EQ(source.read({y0, y2}).values, (std::vector<uint32_t>{1, 0}));
  source.seek(UINT64_MAX);
  EXPECT_EQ(source.cursor_us(), 2999000u);
  source.seek(0);
  EXPECT_EQ(source.cursor_us(), 0u);
}

TEST_F(Replay, StepsByScanClamped) {
  source.step_scans(1);
  EXPECT_EQ(source.cursor_us(), 1000u);
  source.step_scans(-5);
  EXPECT_EQ(source.cursor_us(), 0u);
  source.step_scans(INT64_MAX);
  EXPECT_EQ(source.cursor_us(), 2999000u);
  source.step_scans(-10);
  EXPECT_EQ(source.cursor_us(), 2989000u);
  source.step_scans(INT64_MIN);
  EXPECT_EQ(source.cursor_us(), 0u);
}

TEST_F(Replay, StepsByEventLandOnScansThatChangedSomething) {
  const recording::Reader& rec = source.reader();
  source.seek(995000);
  for (int k = 0; k < 3; ++k) {
    const size_t from = rec.scan_at(source.cursor_us());
    source.step_events(1);
    const size_t to = rec.scan_at(source.cursor_us());
    ASSERT_GT(to, from);
    EXPECT_GT(rec.changes(to), 0u);
    for (size_t i = from + 1; i < to; ++i) EXPECT_EQ(rec.changes(i), 0u) << "scan " << i << " changed";
  }
  // Back by one event: the previous scan that changed something.
  const size_t at = rec.scan_at(source.cursor_us());
  source.step_events(-1);
  const size_t back = rec.scan_at(source.cursor_us());
  EXPECT_LT(back, at);
  EXPECT_GT(rec.changes(back), 0u);
  for (size_t i = back + 1; i < at; ++i) EXPECT_EQ(rec.changes(i), 0u);
  // Past the last event: the cursor stays on the last scan that changed something.
  source.step_events(INT64_MAX);
  const size_t last = rec.scan_at(source.cursor_us());
  EXPECT_GT(rec.changes(last), 0u);
  for (size_t i = last + 1; i < rec.scans(); ++i) EXPECT_EQ(rec.changes(i), 0u);
  source.step_events(INT64_MIN);
  EXPECT_EQ(source.cursor_us(), 0u);  // the first scan changes the first-scan relay
}

TEST_F(Replay, ARecordingIsReadOnly) {
  const auto refused = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refused([&] { source.write(r0, {5}); }), "a recording is read-only");
  EXPECT_EQ(refused([&] { source.force(y0, ForceAction::Disable); }), "a recording is read-only");
  EXPECT_EQ(refused([&] { source.set_mode(RunMode::Stop); }), "a recording is read-only");
  source.seek(2000000);
  EXPECT_EQ(source.read({r0}).values, std::vector<uint32_t>{0});  // nothing written
  const monitor::CellStatus s = source.status();
  EXPECT_FALSE(s.mode_switchable);
  EXPECT_EQ(s.mode, RunMode::Run);
  EXPECT_EQ(s.scan.scans, 2001u);
  EXPECT_NE(s.note.find("recorded run"), std::string::npos);
}

TEST_F(Replay, AnAddressOutsideTheMemoryIsRefusedNamed) {
  Address bad = r0;
  bad.index = 99999;
  EXPECT_THROW(source.read({bad}), Error);
}

}  // namespace
}  // namespace plc_cell
