// When the real-time scan turns WARN and ERROR on /diagnostics (docs/scan-engine.md, "Scan
// health"): overruns and wake latency over the last 10 s, against the configured period.
// Every scan is fed on a virtual clock: what a loaded machine would do, step by step.
#include <gtest/gtest.h>

#include "plc_fixture.h"
#include "plc_cell/core/scan_health.h"

using namespace plc_cell;

namespace {

constexpr uint64_t kPeriodUs = 1000;

// A real-time loop at 1 ms from `from_us` for `seconds`: one period missed (the scan after
// it runs a period late) every `overrun_every` scans (0: none), each wake `latency_us` late.
uint64_t run(ScanWindow* w, uint64_t from_us, double seconds, uint64_t overrun_every, uint64_t latency_us = 20) {
  uint64_t t = from_us, n = 0;
  const uint64_t end = from_us + static_cast<uint64_t>(seconds * 1e6);
  while (t < end) {
    const uint64_t missed = overrun_every && ++n % overrun_every == 0 ? 1 : 0;
    w->add(t, latency_us * 1000, missed);
    t += (1 + missed) * kPeriodUs;
  }
  return t;
}

}  // namespace

TEST(ScanHealth, OverrunsEverySecondTurnTheScanWarn) {
  // 326 overruns in 53 s at 1 ms: one period in 163, about 0.6 % of the periods.
  ScanWindow w;
  const uint64_t t = run(&w, 0, 53, 162);
  const ScanWindow::Summary s = w.summary(t);
  // The last 9 to 10 s only (whole seconds of scan time), not all 326.
  EXPECT_GE(s.overruns, 9e6 / 163e3 - 1);
  EXPECT_LE(s.overruns, 10e6 / 163e3 + 1);
  const ScanHealth h = assess_scan(s, kPeriodUs);
  EXPECT_EQ(h.level, ScanHealthLevel::Warn) << h.reason;
  EXPECT_NE(h.reason.find("periods overrun (0.6"), std::string::npos) << h.reason;
}

TEST(ScanHealth, AnOccasionalOverrunStaysOk) {
  // 0.05 % of the periods (5 in 10 s): under the WARN line of 0.1 %.
  ScanWindow w;
  const uint64_t t = run(&w, 0, 20, 2000);
  const ScanHealth h = assess_scan(w.summary(t), kPeriodUs);
  EXPECT_EQ(h.level, ScanHealthLevel::Ok) << h.reason;
  EXPECT_TRUE(h.reason.empty());
}

TEST(ScanHealth, OverrunsOfMoreThanFivePercentAreAnError) {
  ScanWindow w;
  const uint64_t t = run(&w, 0, 12, 10);  // one period in 11 missed: 819 of the 9001 in the window, 9.10 %
  const ScanHealth h = assess_scan(w.summary(t), kPeriodUs);
  EXPECT_EQ(h.level, ScanHealthLevel::Error) << h.reason;
  EXPECT_NE(h.reason.find("periods overrun (9.10 %)"), std::string::npos) << h.reason;
  // Just under the line: one in 21 (4.8 %) is a WARN.
  ScanWindow under;
  const uint64_t u = run(&under, 0, 12, 20);
  EXPECT_EQ(assess_scan(under.summary(u), kPeriodUs).level, ScanHealthLevel::Warn);
}

TEST(ScanHealth, ABurstLeavesTheWindowAfterTenSeconds) {
  ScanWindow w;
  uint64_t t = run(&w, 5'000'000, 2, 5);  // 2 s of heavy overruns
  EXPECT_EQ(assess_scan(w.summary(t), kPeriodUs).level, ScanHealthLevel::Error);
  t = run(&w, t, 8.5, 0);  // the burst's last second is still in the window
  EXPECT_NE(assess_scan(w.summary(t), kPeriodUs).level, ScanHealthLevel::Ok);
  t = run(&w, t, 3, 0);  // now it is not
  const ScanWindow::Summary s = w.summary(t);
  EXPECT_EQ(s.overruns, 0u);
  EXPECT_GT(s.scans, 9000u);
  EXPECT_EQ(assess_scan(s, kPeriodUs).level, ScanHealthLevel::Ok);
}

TEST(ScanHealth, AWakeLaterThanHalfAPeriodIsAWarning) {
  ScanWindow late;
  uint64_t t = run(&late, 0, 3, 0, 20);
  late.add(t, 600'000, 0);  // one wake 600 us late at 1 ms
  ScanHealth h = assess_scan(late.summary(t), kPeriodUs);
  EXPECT_EQ(h.level, ScanHealthLevel::Warn);
  EXPECT_NE(h.reason.find("woke up to 600 us late, over half the 1000 us period"), std::string::npos) << h.reason;
  // The same 600 us against a 2 ms period is within half of it.
  EXPECT_EQ(assess_scan(late.summary(t), 2000).level, ScanHealthLevel::Ok);
  ScanWindow fine;
  t = run(&fine, 0, 3, 0, 400);
  EXPECT_EQ(assess_scan(fine.summary(t), kPeriodUs).level, ScanHealthLevel::Ok);
}

TEST(ScanHealth, NoRealTimeScansIsOk) {
  // Virtual time reports no cycles: nothing to judge.
  ScanWindow w;
  EXPECT_EQ(assess_scan(w.summary(123'000'000), kPeriodUs).level, ScanHealthLevel::Ok);
}

using ScanHealthEngine = PlcFixture;

TEST_F(ScanHealthEngine, TheEngineKeepsTheWindowOfItsReportedCycles) {
  // What the real-time loop does after each scan, on the fixture's virtual clock.
  load("ORG M1924\nOUT Y0\nEND\n");
  for (int i = 0; i < 12000; ++i) {
    plc.scan(now_us);
    const uint64_t missed = i % 50 == 49 ? 1 : 0;  // 2 % of the scans
    plc.locked([&](ScanEngine& e, Memory&) {
      e.report_cycle(100'000, 30'000, missed);
      return 0;
    });
    now_us += (1 + missed) * kPeriodUs;
  }
  const ScanStats st = plc.locked([](ScanEngine& e, Memory&) { return e.stats(); });
  const ScanWindow::Summary s = st.recent.summary(now_us - kPeriodUs);
  EXPECT_EQ(st.overruns, 240u);
  EXPECT_LT(s.overruns, 240u);
  EXPECT_GT(s.overruns, 170u);
  EXPECT_EQ(s.max_wake_latency_ns, 30'000u);
  EXPECT_EQ(assess_scan(s, kPeriodUs).level, ScanHealthLevel::Warn);
}
