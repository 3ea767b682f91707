// The digital input filter (manual §9.7, spec §1.6): pulses shorter than the
// filter are lost, longer ones arrive the filter time late (a debounce); a
// frequency cut-off loses an input above it.
#include <gtest/gtest.h>

#include <fstream>

#include "hsc_fixture.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {
namespace hsc {
namespace {

constexpr uint64_t kMs = 1000000;  // ns
constexpr uint64_t kUs = 1000;

TEST(Filter, TwoMsFilterOnExactEdges) {
  // Manual: with a 2 ms filter an ON or OFF pulse shorter than 2 ms is lost.
  // HSC0 MD0 counts X0; the ladder copies X0 to Y0 (1 ms scans).
  HscCell cell("counters:\n  hsc0: {mode: MD0}\n  filters: {X0-X3: 2ms}\n", "ORG X0\nOUT Y0\nEND\n");
  cell.with([](HscUnit& u) {
    u.schedule_edge(0, 10 * kMs, true);  // 1.5 ms ON: lost
    u.schedule_edge(0, 11500 * kUs, false);
    u.schedule_edge(0, 20 * kMs, true);  // 3 ms ON: passes, 20+2 .. 23+2
    u.schedule_edge(0, 23 * kMs, false);
    u.schedule_edge(0, 30 * kMs, true);  // ON at 32 ms; the 1.5 ms OFF gap is lost
    u.schedule_edge(0, 40 * kMs, false);
    u.schedule_edge(0, 41500 * kUs, true);
    u.schedule_edge(0, 50 * kMs, false);  // OFF at 52 ms
    return 0;
  });
  cell.run(22000);  // scans 0 .. 21 ms
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 0);
  cell.run(1000);  // the scan at 22 ms: the filter passed the edge at exactly 22 ms
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 1);
  cell.run(40000);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 2);
  const auto y0 = cell.changes_of(0);
  ASSERT_EQ(y0.size(), 4u);
  EXPECT_EQ(y0[0].t_ns, 22 * kMs);
  EXPECT_EQ(y0[1].t_ns, 25 * kMs);
  EXPECT_EQ(y0[2].t_ns, 32 * kMs);
  EXPECT_EQ(y0[3].t_ns, 52 * kMs);
}

TEST(Filter, FilterDelaysAnEdgeInterruptToTheExactInstant) {
  HscCell cell("counters:\n  interrupts: [X6+]\n  filters: {X4-X7: 1.2ms}\n",
               "ORG M1925\nOUT M0\nEND\nLBL X6+I\nORG M1925\nFUN 15 INC D=R0\nRTI\n");
  cell.with([](HscUnit& u) {
    u.schedule_edge(6, 3100 * kUs, true);  // 1.1 ms: lost
    u.schedule_edge(6, 4200 * kUs, false);
    u.schedule_edge(6, 5300 * kUs, true);  // passes at 6.5 ms
    return 0;
  });
  cell.run(10000);
  const auto runs = cell.runs_of(kX0Up + 2 * 6);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0].t_ns, 6500 * kUs);
  EXPECT_EQ(cell.get("R0"), 1u);
}

TEST(Filter, TenthMsFilterOnPulseTrains) {
  // 0.3 ms filters; 1 ms trains. X4: 0.2 ms pulses, all lost. X8: 0.4 ms pulses,
  // each passes 0.3 ms late: rises at 0.3, 1.3, ... 98.3 ms before the scan at
  // 99 ms: 99. X12: 0.8 ms pulses with 0.2 ms gaps: the gaps are lost, one rise.
  HscCell cell("counters:\n  hsc4: {mode: MD0, a: X4}\n  hsc5: {mode: MD0, a: X8}\n  hsc6: {mode: MD0, a: X12}\n"
               "  filters: {X4-X7: 0.3ms, X8-X11: 0.3ms, X12-X15: 0.3ms}\n",
               "ORG M1925\nOUT M0\nEND\n");
  cell.with([](HscUnit& u) {
    u.add_pulse_train(4, 1 * kMs, 200 * kUs, 0);
    u.add_pulse_train(8, 1 * kMs, 400 * kUs, 0);
    u.add_pulse_train(12, 1 * kMs, 800 * kUs, 0);
    return 0;
  });
  cell.run(100000);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(4); }), 0);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(5); }), 99);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(6); }), 1);
}

TEST(Filter, FrequencyCutOffLosesFasterEncoders) {
  // Manual: with a 28 kHz filter an input above 28 kHz is lost. The selection
  // passes half-periods >= 1/(2 x 28125 Hz) = 17.8 us. A/B x4 for 10 ms:
  // HSC0 40 kHz filtered: 0; HSC1 20 kHz filtered: 4 x 20000 x 0.01 = 800;
  // HSC2 40 kHz unfiltered: 1600.
  HscCell cell("counters:\n  hsc0: {mode: MD7}\n  hsc1: {mode: MD7}\n  hsc2: {mode: MD7}\n"
               "  filters: {X0-X3: 28kHz, X4-X7: 28kHz}\n"
               "  sources:\n    - {name: e40, type: encoder, a: X0, hz: 40000}\n"
               "    - {name: e20, type: encoder, a: X4, hz: 20000}\n"
               "    - {name: raw40, type: encoder, a: X8, hz: 40000}\n",
               "ORG X0\nOUT Y0\nEND\n");
  cell.run(10001);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 0);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(1); }), 800);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(2); }), 1600);
  EXPECT_TRUE(cell.changes_of(0).empty());  // the lost input stays OFF in the image
  // Slowed below the cut-off, it counts again from there: 4 x 20000 x 0.01 more.
  cell.with([](HscUnit& u) {
    u.set_source_rate("e40", 20000);
    return 0;
  });
  cell.run(10000);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 800);
}

TEST(Filter, TwoMsFilterOnScanSampledInput) {
  // X16 is sampled at the 1 ms scans: ON sampled at 10, 11 ms (1.5 ms pulse) is
  // lost; ON at 20, 21, 22 ms (3 ms pulse) passes at 22 ms, OFF sampled at 23 ms
  // passes at 25 ms.
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/filter16.il") << "ORG X16\nCTR C0 100\nORG X16\nOUT Y0\nEND\n";
  std::ofstream(dir + "/filter16.yaml")
      << "cell: {program: filter16.il}\n"
         "simulation:\n  inputs:\n    X16: {steps: [[0.010, 1], [0.0115, 0], [0.020, 1], [0.023, 0]]}\n"
         "counters:\n  filters: {X16-X23: 2ms}\n";
  SoftCell cell(dir + "/filter16.yaml", "");
  std::vector<std::pair<uint64_t, bool>> y0;
  cell.plc().locked([&](ScanEngine&, Memory&) {
    cell.get<hsc::HscUnit>()->on_output([&](uint64_t t, uint32_t y, bool v) {
      if (y == 0) y0.push_back({t, v});
    });
    return 0;
  });
  ASSERT_TRUE(cell.plc().set_mode(RunMode::Run));
  for (uint64_t t = 0; t < 40000; t += 1000) cell.plc().scan(t);
  EXPECT_EQ(cell.plc().read(parse_address("RC0"), 1).at(0), 1u);
  ASSERT_EQ(y0.size(), 2u);
  EXPECT_EQ(y0[0], std::make_pair(22 * kMs, true));
  EXPECT_EQ(y0[1], std::make_pair(25 * kMs, false));
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
