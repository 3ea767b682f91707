// A recording of `plc_cell sim --record` gives back, at every instant, the memory a fresh
// run of the same cell has at that instant: the whole image, not only a few addresses.
#include <gtest/gtest.h>

#include "helpers.h"
#include "plc_cell/recording/reader.h"

namespace plc_cell {
namespace {

using testing::ConveyorRun;

TEST(RecordingRoundTrip, EveryInstantAsAFreshRunOfTheDemo) {
  const std::string dir = testing::scratch_dir("round_trip");
  const std::string path = testing::record_conveyor(dir, "40s");
  const recording::Reader rec = recording::Reader::load(path);
  ASSERT_EQ(rec.scans(), 40000u);  // 1 ms scans
  EXPECT_EQ(rec.scan_us(0), 0u);
  EXPECT_EQ(rec.scan_us(39999), 39999000u);
  EXPECT_GE(rec.keyframes(), 3u);  // the instants below are rebuilt from several
  EXPECT_EQ(rec.info().program_file, "conveyor.il");
  EXPECT_NE(rec.info().program_text.find("OUT"), std::string::npos);
  EXPECT_EQ(rec.info().scan_period_us, 1000u);
  ASSERT_FALSE(rec.info().signals.empty());
  EXPECT_EQ(rec.info().signals[0].first, "start_button");
  EXPECT_FALSE(rec.info().failure_us);

  ConveyorRun fresh;
  // Before, at and after the part's arrival (1 s), the robot's 1.5 s, the second part
  // (6 s), around the keyframes after 16384 and 32768 scans, and the last scan.
  for (uint64_t t : {0ull, 1ull, 999000ull, 1000000ull, 1001000ull, 2500000ull, 2501000ull, 6000000ull,
                     16383000ull, 16384000ull, 16385000ull, 32767000ull, 32768000ull, 39999000ull}) {
    const recording::Image expected = fresh.image_after(t);
    const size_t i = rec.scan_at(t);
    EXPECT_EQ(rec.scan_us(i), t / 1000 * 1000);
    recording::Image got;
    rec.image_after(i, &got);
    EXPECT_TRUE(got.bits == expected.bits) << "bits differ at t = " << t << " us";
    EXPECT_TRUE(got.words == expected.words) << "words differ at t = " << t << " us";
  }
}

TEST(RecordingRoundTrip, TheSameRunRecordsTheSameBytes) {
  const std::string dir = testing::scratch_dir("twice");
  const std::string a = testing::file_bytes(testing::record_conveyor(dir, "2s", "a"));
  const std::string b = testing::file_bytes(testing::record_conveyor(dir, "2s", "b"));
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(a == b);
}

TEST(RecordingRoundTrip, TheInitialImageIsTheMemoryBeforeTheFirstScan) {
  const std::string dir = testing::scratch_dir("initial");
  const recording::Reader rec = recording::Reader::load(testing::record_conveyor(dir, "10ms"));
  ConveyorRun fresh;
  recording::Image before;
  fresh.cell.plc().locked([&](ScanEngine&, Memory& m) {
    recording::capture(m, &before);
    return 0;
  });
  EXPECT_TRUE(rec.initial().bits == before.bits);
  EXPECT_TRUE(rec.initial().words == before.words);
  EXPECT_EQ(rec.initial_mode(), RunMode::Run);
  Memory clock;
  recording::restore(rec.initial(), &clock);
  EXPECT_EQ(clock.reg(Area::R, 4133), 26u);  // the cell's RTC start, 2026-01-01
  EXPECT_EQ(clock.reg(Area::R, 4128), 0u);
  // M1924 (first scan) is on after the first scan only.
  recording::Image first, second;
  rec.image_after(0, &first);
  rec.image_after(1, &second);
  Memory m;
  recording::restore(first, &m);
  EXPECT_TRUE(m.bit(Area::M, special::kFirstScan));
  recording::restore(second, &m);
  EXPECT_FALSE(m.bit(Area::M, special::kFirstScan));
}

TEST(RecordingRoundTrip, SimRefusesAFileItCannotWrite) {
  const auto r = testing::run_tool("sim --config " + testing::kConveyorYaml +
                                   " --duration 10ms --record /nonexistent_dir/run.plcrec");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("cannot write the recording /nonexistent_dir/run.plcrec"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace plc_cell
