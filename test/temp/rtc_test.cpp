// The FBs real-time clock (R4128-R4135, M1952-M1955, D4053/D4054) in virtual time.
#include <gtest/gtest.h>

#include <ctime>
#include <string>
#include <utility>
#include <vector>

#include "../core/plc_fixture.h"
#include "plc_cell/core/error.h"
#include "plc_cell/temp/rtc.h"
#include "plc_cell/temp/rtc_calibration.h"

namespace plc_cell {
namespace temp {
namespace {

TEST(RtcCalendar, SecondsRoundTripAndWeekdays) {
  const DateTime t{2026, 1, 1, 0, 0, 0};
  EXPECT_EQ(weekday(to_seconds(t)), 4);  // 2026-01-01 is a Thursday
  EXPECT_EQ(weekday(to_seconds({2000, 1, 1, 0, 0, 0})), 6);
  EXPECT_EQ(weekday(to_seconds({2024, 2, 29, 12, 0, 0})), 4);
  for (int64_t s : {int64_t(0), to_seconds({2024, 2, 29, 23, 59, 59}), to_seconds({2099, 12, 31, 23, 59, 59})}) {
    const DateTime d = from_seconds(s);
    EXPECT_EQ(to_seconds(d), s);
  }
  const DateTime leap = from_seconds(to_seconds({2024, 2, 28, 23, 59, 59}) + 1);
  EXPECT_EQ(leap.month, 2);
  EXPECT_EQ(leap.day, 29);
  EXPECT_FALSE(valid({2023, 2, 29, 0, 0, 0}));
  EXPECT_TRUE(parse_date_time("2026-01-01T00:00:00").has_value());
  EXPECT_TRUE(parse_date_time("2026-07-31 23:59:59").has_value());
  EXPECT_FALSE(parse_date_time("2026-13-01T00:00:00").has_value());
  EXPECT_FALSE(parse_date_time("1999-12-31T00:00:00").has_value());
  EXPECT_FALSE(parse_date_time("2026-01-01T00:00:00Z").has_value());
}

TEST(RtcCalibration, TheManualsExamplesAndTable) {
  // Manual 15.3: a clock 3.38 s/day fast -> 56E5H; 5.62 s/day slow -> 5603H.
  EXPECT_EQ(rtc_calibration_code(3.38), 0x56E5);
  EXPECT_EQ(rtc_calibration_code(-5.62), 0x5603);
  EXPECT_DOUBLE_EQ(*rtc_calibration_rate(0x56E5), 3.38);
  EXPECT_DOUBLE_EQ(*rtc_calibration_rate(0x5603), -5.62);
  EXPECT_DOUBLE_EQ(*rtc_calibration_rate(0x56FC), 16.61);  // the ends of the range
  EXPECT_DOUBLE_EQ(*rtc_calibration_rate(0x5602), -16.88);
  EXPECT_DOUBLE_EQ(*rtc_calibration_rate(0x0000), 0.0);
  EXPECT_DOUBLE_EQ(*rtc_calibration_rate(0x5681), 0.09);
  EXPECT_DOUBLE_EQ(*rtc_calibration_rate(0x56FF), -0.09);
  // The printed duplicate 5618H is +6.36; +2.05 takes the column's 5619H.
  EXPECT_DOUBLE_EQ(*rtc_calibration_rate(0x5618), 6.36);
  EXPECT_DOUBLE_EQ(*rtc_calibration_rate(0x5619), 2.05);
  EXPECT_DOUBLE_EQ(*rtc_calibration_rate(0x56C8), 1.63);
  EXPECT_DOUBLE_EQ(*rtc_calibration_rate(0x56C9), 1.63);
  EXPECT_FALSE(rtc_calibration_rate(0x1234).has_value());
  // Every code of the table is 56xxH and reads back its own rate.
  int found = 0;
  for (int c = 0x5600; c <= 0x56FF; ++c)
    if (const auto r = rtc_calibration_rate(static_cast<uint16_t>(c))) {
      ++found;
      EXPECT_GE(*r, -16.88);
      EXPECT_LE(*r, 16.61);
    }
  // The manual's 213 56xxH entries (5618H printed twice) with +2.05 as 5619H: 213
  // codes, and 56C9H beside the printed 56C8H.
  EXPECT_EQ(found, 214);
}

class RtcTest : public PlcFixture {
 protected:
  void setup(const std::string& yaml, const std::string& program, const CellClock& clock = {}) {
    const YAML::Node doc = YAML::Load(yaml);
    plc.locked([&](ScanEngine& e, Memory& m) {
      rtc = make_rtc(doc, "cell.yaml", m, clock);
      e.add_hook(rtc.get());
      return 0;
    });
    load(program);
  }
  void TearDown() override {
    if (rtc)
      plc.locked([&](ScanEngine& e, Memory&) {
        e.remove_hook(rtc.get());
        return 0;
      });
  }
  std::unique_ptr<Rtc> rtc;
};

const char* kStart = "modules:\n  rtc: {start: 2026-01-01T23:59:58}\n";
const char* kIdle = "ORG M1925\nOUT M0\nEND\n";

TEST_F(RtcTest, FollowsTheVirtualClockFromTheConfiguredStart) {
  setup(kStart, kIdle);
  scans(1, 100000);
  EXPECT_EQ(get("R4128"), 58u);
  EXPECT_EQ(get("R4129"), 59u);
  EXPECT_EQ(get("R4130"), 23u);
  EXPECT_EQ(get("R4131"), 1u);
  EXPECT_EQ(get("R4132"), 1u);
  EXPECT_EQ(get("R4133"), 26u);  // two-digit year
  EXPECT_EQ(get("R4134"), 4u);   // Thursday
  EXPECT_EQ(get("R4135"), 0x173Bu);  // hour << 8 | minute
  EXPECT_TRUE(get("M1954"));
  EXPECT_EQ(get("D4053"), 3u);
  scans(20, 100000);  // the 20th scan is at t = 2.0 s: midnight
  EXPECT_EQ(get("R4128"), 0u);
  EXPECT_EQ(get("R4129"), 0u);
  EXPECT_EQ(get("R4130"), 0u);
  EXPECT_EQ(get("R4131"), 2u);
  EXPECT_EQ(get("R4134"), 5u);  // Friday
  scans(36000, 100000);  // one hour more
  EXPECT_EQ(get("R4130"), 1u);
  EXPECT_EQ(get("R4129"), 0u);
}

// A host link or Modbus master may read the clock before the first scan, and between
// STOP -> RUN (which clears the non-retentive registers) and the next scan.
TEST_F(RtcTest, TheRegistersHoldTheClockBeforeTheFirstScan) {
  const YAML::Node doc = YAML::Load(kStart);
  plc.locked([&](ScanEngine& e, Memory& m) {
    rtc = make_rtc(doc, "cell.yaml", m);
    e.add_hook(rtc.get());
    return 0;
  });
  // Attached, not a scan yet: 2026-01-01 (a Thursday) 23:59:58.
  EXPECT_EQ(get("R4128"), 58u);
  EXPECT_EQ(get("R4130"), 23u);
  EXPECT_EQ(get("R4131"), 1u);
  EXPECT_EQ(get("R4132"), 1u);
  EXPECT_EQ(get("R4133"), 26u);
  EXPECT_EQ(get("R4134"), 4u);
  EXPECT_EQ(get("R4135"), 0x173Bu);
  load(kIdle);  // STOP -> RUN clears R4128-R4135: they are the clock again at once
  EXPECT_EQ(get("R4132"), 1u);
  EXPECT_EQ(get("R4133"), 26u);
  EXPECT_EQ(get("R4131"), 1u);
}

TEST_F(RtcTest, AWriteToTheClockRegistersIsOverwrittenAtTheNextScanInTheSameSecond) {
  setup(kStart, "ORG X0\nMOV S=99 D=R4129\nEND\n");
  scans(1, 1000);  // 23:59:58.000
  put("R4128", 7);  // a client, between two scans of one second
  put("R4135", 0);
  scans(1, 1000);
  EXPECT_EQ(get("R4128"), 58u);
  EXPECT_EQ(get("R4135"), 0x173Bu);
  input(0, true);  // the program writes the minute: the next scan shows the clock again
  scans(1, 1000);
  EXPECT_EQ(get("R4129"), 99u);
  input(0, false);
  scans(1, 1000);
  EXPECT_EQ(get("R4129"), 59u);
  EXPECT_EQ(get("R4128"), 58u);
}

TEST_F(RtcTest, KeepsRunningInStop) {
  setup(kStart, kIdle);
  scans(1, 1000000);
  plc.set_mode(RunMode::Stop);
  scans(62, 1000000);  // a minute in STOP: the registers are not refreshed, the clock runs
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  scans(1, 1000000);  // at t = 63 s
  EXPECT_EQ(get("R4131"), 2u);
  EXPECT_EQ(get("R4129"), 1u);
  EXPECT_EQ(get("R4128"), 1u);  // 23:59:58 + 63 s = 00:01:01
}

// The manual's setting procedure: M1952 = 1, MOV the values, M1952 1 -> 0.
const char* kSetProgram =
    "ORG X0\nOUT M1952\n"
    "ORG X1\nMOV S=30 D=R4128\nMOV S=15 D=R4129\nMOV S=8 D=R4130\nMOV S=24 D=R4131\n"
    "MOV S=12 D=R4132\nMOV S=27 D=R4133\nMOV S=5 D=R4134\n"
    "ORG X2\nMOV S=31 D=R4131\nMOV S=2 D=R4132\n"
    "ORG X3\nOUT M1953\nEND\n";

TEST_F(RtcTest, TheProgramSetsTheClockOnTheFallingEdgeOfM1952) {
  setup(kStart, kSetProgram);
  scans(1);
  input(0, true);
  input(1, true);
  scans(5);
  EXPECT_EQ(get("R4131"), 24u);  // the program's values are not overwritten while M1952 = 1
  EXPECT_EQ(get("R4129"), 15u);
  input(1, false);
  scans(5000);
  EXPECT_EQ(get("R4128"), 30u);  // and the clock has not been set yet
  input(0, false);
  scans(1);  // M1952 falls at the end of this scan
  scans(1);
  EXPECT_FALSE(get("M1955"));
  EXPECT_EQ(get("R4130"), 8u);
  EXPECT_EQ(get("R4129"), 15u);
  EXPECT_EQ(get("R4128"), 30u);
  EXPECT_EQ(get("R4131"), 24u);
  EXPECT_EQ(get("R4132"), 12u);
  EXPECT_EQ(get("R4133"), 27u);
  EXPECT_EQ(get("R4134"), 5u);  // 2027-12-24 is a Friday
  scans(2000);
  EXPECT_EQ(get("R4128"), 32u);  // timing has resumed
  EXPECT_EQ(rtc->now().year, 2027);
}

TEST_F(RtcTest, AnIllegalSettingSetsM1955AndKeepsTheTime) {
  setup(kStart, kSetProgram);
  scans(1);
  input(0, true);
  input(1, true);
  input(2, true);  // 31 February
  scans(2);
  input(0, false);
  input(1, false);
  input(2, false);
  scans(2);
  EXPECT_TRUE(get("M1955"));
  EXPECT_EQ(get("R4131"), 1u);  // the clock kept 2026-01-01
  EXPECT_EQ(get("R4133"), 26u);
  input(0, true);  // a legal setting clears the flag
  input(1, true);
  scans(2);
  input(0, false);
  input(1, false);
  scans(2);
  EXPECT_FALSE(get("M1955"));
  EXPECT_EQ(get("R4131"), 24u);
}

TEST_F(RtcTest, ThirtySecondAdjustment) {
  // The manual's example: M1953 rising at 12:05:42 -> 12:06:00; below 30 s -> the minute.
  setup("modules:\n  rtc: {start: 2026-03-10T12:05:42}\n", kSetProgram);
  scans(1);
  input(3, true);
  scans(2);
  EXPECT_EQ(get("R4130"), 12u);
  EXPECT_EQ(get("R4129"), 6u);
  EXPECT_EQ(get("R4128"), 0u);
  scans(1000);  // held on: one adjustment only
  EXPECT_EQ(get("R4129"), 6u);
  EXPECT_EQ(get("R4128"), 1u);
  input(3, false);
  scans(28000);  // 12:06:29
  EXPECT_EQ(get("R4128"), 29u);
  input(3, true);
  scans(2);
  EXPECT_EQ(get("R4129"), 6u);
  EXPECT_EQ(get("R4128"), 0u);
}

TEST_F(RtcTest, DriftAndTheManualsCalibration) {
  // A crystal 3.38 s/day fast: a virtual day later the clock is 3.38 s ahead; with
  // D4054 = 56E5H (the manual's example for that error) it is exact.
  setup("modules:\n  rtc: {start: 2026-01-01T00:00:00, drift: 3.38}\n", kIdle);
  scans(1, 1000000);
  scans(86400, 1000000);
  EXPECT_EQ(rtc->seconds() - to_seconds({2026, 1, 2, 0, 0, 0}), 3);  // 3.38 s, whole seconds
  put("D4054", 0x56E5);
  const int64_t before = rtc->seconds();
  scans(86400, 1000000);
  EXPECT_EQ(rtc->seconds() - before, 86400);
}

TEST_F(RtcTest, ASlowClockCorrectedBy5603H) {
  setup("modules:\n  rtc: {start: 2026-01-01T00:00:00, drift: -5.62}\n", kIdle);
  scans(1, 1000000);
  scans(86400, 1000000);
  EXPECT_EQ(rtc->seconds() - to_seconds({2026, 1, 1, 23, 59, 54}), 0);  // 5.62 s behind
  put("D4054", 0x5603);
  const int64_t before = rtc->seconds();
  scans(10 * 86400, 1000000);
  EXPECT_EQ(rtc->seconds() - before, 10 * 86400);
}

// An exact crystal needs no drift arithmetic, but a calibration code written while it
// runs still changes its rate from that scan on: D4054 = 56E5H corrects a crystal 3.38 s/day
// fast, so an exact one loses 3.38 s a day.
TEST_F(RtcTest, ACalibrationWrittenToAnExactClockTakesEffectAtTheNextScan) {
  setup("modules:\n  rtc: {start: 2026-01-01T00:00:00}\n", kIdle);
  scans(1, 1000000);
  int64_t before = rtc->seconds();
  scans(86400, 1000000);
  EXPECT_EQ(rtc->seconds() - before, 86400);
  put("D4054", 0x56E5);
  before = rtc->seconds();
  scans(86400, 1000000);
  EXPECT_EQ(rtc->seconds() - before, 86396);  // 86396.62 s
  put("D4054", 0);
  before = rtc->seconds();
  scans(3600, 1000000);
  EXPECT_EQ(rtc->seconds() - before, 3600);
}

int64_t host_local_seconds() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  localtime_r(&now, &tm);
  return to_seconds({tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec});
}

const CellClock kRealTime{false, ""};

TEST_F(RtcTest, InRealTimeWithoutAStartItReadsTheHostsLocalTime) {
  setup("cell: {name: x}\n", kIdle, kRealTime);
  scans(1);
  EXPECT_NEAR(double(rtc->seconds()), double(host_local_seconds()), 5.0);  // where it starts, not how fast it runs
  EXPECT_EQ(get("R4133"), uint32_t(rtc->now().year - 2000));
}

// Virtual time is deterministic: the same run gives the same registers whenever it is made.
TEST_F(RtcTest, InVirtualTimeWithoutAStartItStartsAtTheDocumentedInstant) {
  setup("cell: {name: x}\n", kIdle);  // a cell's clock is virtual unless said otherwise
  scans(1);
  // 2024-01-01T00:00:00, a Monday (docs/analog-and-temperature.md, "Real-time clock").
  EXPECT_EQ(std::string(kVirtualCalendarStart), "2024-01-01T00:00:00");
  for (const auto& [reg, v] : std::vector<std::pair<const char*, uint32_t>>{
           {"R4128", 0}, {"R4129", 0}, {"R4130", 0}, {"R4131", 1}, {"R4132", 1}, {"R4133", 24}, {"R4134", 1},
           {"R4135", 0}})
    EXPECT_EQ(get(reg), v) << reg;
}

// modules.rtc.start wins over the clock's default, --rtc-start (calendar_start) over both.
TEST_F(RtcTest, TheCellsCalendarStartWinsOverTheFilesStart) {
  setup(kStart, kIdle, CellClock{true, "2030-06-15T12:30:00"});
  scans(1);
  EXPECT_EQ(get("R4133"), 30u);
  EXPECT_EQ(get("R4132"), 6u);
  EXPECT_EQ(get("R4131"), 15u);
  EXPECT_EQ(get("R4135"), 0x0C1Eu);  // 12:30
}

TEST_F(RtcTest, HostAsTheCalendarStartReadsTheHostEvenInVirtualTime) {
  setup(kStart, kIdle, CellClock{true, "host"});
  scans(1);
  EXPECT_NEAR(double(rtc->seconds()), double(host_local_seconds()), 5.0);
}

// The two halves of a lockstep cell take one reading of the host's clock.
TEST_F(RtcTest, AGivenHostTimeIsTheHostsLocalTime) {
  setup("cell: {name: x}\n", kIdle, kRealTime);
  const std::time_t t = 1700000000;  // 2023-11-14 22:13:20 UTC
  rtc->set_host_time(int64_t(t));
  scans(1);
  std::tm tm{};
  localtime_r(&t, &tm);
  EXPECT_EQ(rtc->seconds(),
            to_seconds({tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec}));
}

TEST(RtcConfig, ABadCalendarStartIsRefused) {
  Memory m;
  try {
    make_rtc(YAML::Node(), "c.yaml", m, CellClock{true, "2030-02-30T00:00:00"});
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "RTC start 2030-02-30T00:00:00: expected host or a date-time 2000-01-01T00:00:00 .. 2099-12-31T23:59:59");
  }
}

TEST(RtcConfig, KeysAreChecked) {
  EXPECT_THROW(parse_rtc_config(YAML::Load("{start: 2026-02-30T00:00:00}"), "c.yaml"), SourceError);
  EXPECT_THROW(parse_rtc_config(YAML::Load("{begin: 2026-01-01T00:00:00}"), "c.yaml"), SourceError);
  const RtcConfig c = parse_rtc_config(YAML::Load("start: 2026-01-01T00:00:00\ndrift: -5.62\n"), "c.yaml");
  EXPECT_TRUE(c.has_start);
  EXPECT_DOUBLE_EQ(c.drift_s_per_day, -5.62);
  EXPECT_FALSE(parse_rtc_config(YAML::Node(), "c.yaml").has_start);  // the host's time
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
