// A recorded run as the monitor's source: the cursor's moves (seek, by scan, by event),
// clamped to the run, the values at the cursor, and every change refused.
#include <gtest/gtest.h>

#include "helpers.h"
#include "plc_cell/recording/recorder.h"
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

// Whether scan i changed one of cells.
bool changed(const recording::Reader& rec, size_t i, const std::vector<bool>& cells) {
  bool any = false;
  rec.each_change(i, i, [&](size_t, uint32_t cell, uint16_t) {
    any = any || cells[cell];
    return !any;
  });
  return any;
}

TEST_F(Replay, StepsByEventLandOnChangesOfTheProgramsAddresses) {
  const recording::Reader& rec = source.reader();
  const std::vector<bool>& events = source.event_cells();
  const std::vector<bool> all(events.size(), true);
  // From the first scan the next event is the part reaching the stopper at 1 s: the 0.01 s
  // clock relay M1920 changes every 5 ms before it, and is not one.
  source.step_events(1, {});
  EXPECT_EQ(source.cursor_us(), 1000000u);
  EXPECT_GT(rec.next_change(0, 1, all), 0u);
  EXPECT_LT(rec.next_change(0, 1, all), 20u);
  for (uint32_t c : recording::cells_of(parse_address("M1920"))) EXPECT_FALSE(events[c]);
  for (uint32_t c : recording::cells_of(parse_address("R4128"))) EXPECT_FALSE(events[c]);
  for (const char* a : {"X3", "Y0", "M0", "RT50", "R0", "Y77"})
    for (uint32_t c : recording::cells_of(parse_address(a))) EXPECT_TRUE(events[c]) << a;
  for (int k = 0; k < 3; ++k) {
    const size_t from = rec.scan_at(source.cursor_us());
    source.step_events(1, {});
    const size_t to = rec.scan_at(source.cursor_us());
    ASSERT_GT(to, from);
    EXPECT_TRUE(changed(rec, to, events));
    for (size_t i = from + 1; i < to; ++i) EXPECT_FALSE(changed(rec, i, events)) << "scan " << i;
  }
  // Back by one event: the previous scan that changed one of them.
  const size_t at = rec.scan_at(source.cursor_us());
  source.step_events(-1, {});
  const size_t back = rec.scan_at(source.cursor_us());
  EXPECT_LT(back, at);
  EXPECT_TRUE(changed(rec, back, events));
  for (size_t i = back + 1; i < at; ++i) EXPECT_FALSE(changed(rec, i, events));
  // Past the last event: the cursor stays on the last scan that changed one.
  source.step_events(INT64_MAX, {});
  const size_t last = rec.scan_at(source.cursor_us());
  EXPECT_TRUE(changed(rec, last, events));
  for (size_t i = last + 1; i < rec.scans(); ++i) EXPECT_FALSE(changed(rec, i, events));
  source.step_events(INT64_MIN, {});
  EXPECT_EQ(source.cursor_us(), 0u);  // the first scan starts the line (M0, Y0)
}

// A run made here: X0 drives Y0, and between the scans D5 (no address of the program) and
// the real-time clock's R4128 are written as a client would.
std::string made_run() {
  Plc plc;
  plc.load_program_text("ORG X0\nOUT Y0\nEND\n", "made.il");
  plc.set_mode(RunMode::Run);
  recording::RecordingInfo info;
  info.source = "test";
  info.program_file = "made.il";
  info.program_text = "ORG X0\nOUT Y0\nEND\n";
  info.scan_period_us = 1000;
  recording::Recorder rec(info);
  rec.start(plc);
  for (uint64_t i = 0; i < 40; ++i) {
    if (i == 10) plc.write(parse_address("D5"), {7});
    if (i == 15) plc.write(parse_address("R4128"), {30});
    if (i == 20) plc.set_input(0, true);
    if (i == 25) plc.write(parse_address("D5"), {8});
    if (i == 30) plc.write(parse_address("DR10"), {0x00020001});
    plc.scan(i * 1000);
    rec.scanned(plc, i * 1000);
  }
  return rec.bytes();
}

TEST(ReplayEvents, TheWatchTableAddsItsAddressesButNeverTheClocks) {
  recording::ReplaySource src{recording::Reader::parse(made_run(), "made.plcrec"), "made.plcrec",
                              SoftCell::functions()};
  src.step_events(1, {});
  EXPECT_EQ(src.cursor_us(), 20000u);  // X0 and Y0: D5 and R4128 are no address of the program
  src.seek(0);
  src.step_events(1, {parse_address("D5"), parse_address("R4128")});
  EXPECT_EQ(src.cursor_us(), 10000u);  // D5, watched
  src.step_events(1, {parse_address("D5"), parse_address("R4128")});
  EXPECT_EQ(src.cursor_us(), 20000u);  // the watched R4128 at 15 ms is the clock's
  src.step_events(1, {parse_address("D5")});
  EXPECT_EQ(src.cursor_us(), 25000u);
  src.step_events(-2, {parse_address("D5")});
  EXPECT_EQ(src.cursor_us(), 10000u);
}

TEST(ReplayEvents, HistoryIsEveryRecordedChange) {
  recording::ReplaySource src{recording::Reader::parse(made_run(), "made.plcrec"), "made.plcrec",
                              SoftCell::functions()};
  using Points = std::vector<std::pair<uint64_t, uint32_t>>;
  const monitor::History h =
      src.history({parse_address("D5"), parse_address("Y0"), parse_address("DR10"), parse_address("WY0")}, 0, 39000);
  EXPECT_FALSE(h.cut_us);
  ASSERT_EQ(h.series.size(), 4u);
  EXPECT_EQ(h.series[0], (Points{{0, 0}, {10000, 7}, {25000, 8}}));
  EXPECT_EQ(h.series[1], (Points{{0, 0}, {20000, 1}}));
  EXPECT_EQ(h.series[2], (Points{{0, 0}, {30000, 0x00020001}}));
  EXPECT_EQ(h.series[3], (Points{{0, 0}, {20000, 1}}));
  // From an instant inside the run: the value then, and what changed after up to to_us.
  EXPECT_EQ(src.history({parse_address("D5")}, 12500, 24999).series[0], (Points{{12000, 7}}));
  EXPECT_EQ(src.history({parse_address("D5")}, 12500, 99999).series[0], (Points{{12000, 7}, {25000, 8}}));
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
