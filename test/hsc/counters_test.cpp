// Counters against hand-made edge sequences and analytic encoders, in virtual time.
#include "hsc_fixture.h"

#include <cmath>

namespace plc_cell {
namespace hsc {
namespace {

constexpr uint64_t kMs = 1000000;  // ns

const char* kIdle = "ORG M1925\nOUT M0\nEND\n";

TEST(Counters, Md0SimultaneousEdgesCancelAndMaskClearWindows) {
  // HSC4 (software) counts U on X4, D on X5, MASK on X6, CLEAR on X7.
  HscCell cell("counters:\n  hsc4: {mode: MD0, a: X4, b: X5, mask: X6, clear: X7}\n", kIdle);
  auto pulse = [&](int x, uint64_t t) {
    cell.with([&](HscUnit& u) {
      u.schedule_edge(x, t, true);
      u.schedule_edge(x, t + 100000, false);
      return 0;
    });
  };
  for (int k = 0; k < 5; ++k) pulse(4, (1 + k) * kMs);            // +5
  pulse(4, 7 * kMs);                                                 // U and D at once: 0
  pulse(5, 7 * kMs);
  pulse(5, 8 * kMs);                                                 // -1 -> 4
  cell.with([&](HscUnit& u) {
    u.schedule_edge(6, 10 * kMs, true);                              // MASK 10..12 ms
    u.schedule_edge(6, 12 * kMs, false);
    return 0;
  });
  pulse(4, 11 * kMs);                                                // masked
  pulse(4, 13 * kMs);                                                // -> 5
  cell.run(9000, 1000);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(4); }), 4);
  EXPECT_EQ(cell.get("DR4112"), 4u);  // a software counter's CV is its register
  cell.run(6000, 1000);
  EXPECT_EQ(cell.get("DR4112"), 5u);
  cell.with([&](HscUnit& u) {
    u.schedule_edge(7, 16 * kMs, true);   // CLEAR 16..18 ms: CV 0, no counting
    u.schedule_edge(7, 18 * kMs, false);
    return 0;
  });
  pulse(4, 17 * kMs);
  pulse(4, 19 * kMs);
  cell.run(6000, 1000);
  EXPECT_EQ(cell.get("DR4112"), 1u);
}

TEST(Counters, AbDirectionReversalFromEdges) {
  // HSC0 A/B x4 on X0/X1 from an explicit Gray sequence: 6 steps forward, 2 back.
  HscCell cell("counters:\n  hsc0: {mode: MD7}\n", kIdle);
  const bool seq[][2] = {{1, 0}, {1, 1}, {0, 1}, {0, 0}, {1, 0}, {1, 1}, {1, 0}, {0, 0}};
  cell.with([&](HscUnit& u) {
    for (int i = 0; i < 8; ++i) {
      u.schedule_edge(0, (i + 1) * 100000, seq[i][0]);
      u.schedule_edge(1, (i + 1) * 100000, seq[i][1]);
    }
    return 0;
  });
  cell.run(2000, 1000);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 4);
}

TEST(Counters, AbModesOnAnAnalyticEncoderWithReversal) {
  // The same encoder on four counters: x1 (software, X0/X1) is not possible beside
  // HSC0, so each mode gets its own cell. 1 kHz for 1 s forward, then 0.25 s back.
  const int mult[4] = {1, 2, 3, 4};
  for (int m = 0; m < 4; ++m) {
    const std::string yaml = "counters:\n  hsc2: {mode: MD" + std::to_string(4 + m) +
                             "}\n  sources:\n    - {name: enc, type: encoder, a: X8, hz: 1000}\n";
    HscCell cell(yaml, kIdle);
    cell.run(1000000, 1000);  // scans at 0 .. 0.999 s
    cell.run(1000, 1000);     // t = 1.000 s
    EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(2); }), 1000 * mult[m]) << "MD" << 4 + m;
    cell.with([](HscUnit& u) {
      u.set_source_rate("enc", -1000.0);
      return 0;
    });
    cell.run(250000, 1000);
    EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(2); }), 750 * mult[m]) << "MD" << 4 + m;
  }
}

TEST(Counters, PulseDirectionFromTheSoftwareRelayTakesEffectAfterTheScan) {
  // HSC1 MD2: P on X4 from a 1 kHz generator; R from M1948 (no R input).
  HscCell cell("counters:\n  hsc1: {mode: MD2, a: X4}\n  sources:\n    - {name: gen, a: X4, hz: 1000}\n",
               "ORG M100\nOUT M1948\nEND\n");
  cell.run(100000, 1000);  // 0 .. 99 ms scans; counted up to 99 ms
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(1); }), 99);
  cell.put("M100", 1);
  cell.run(50000, 1000);  // the relay reaches the counter at the end of the 100 ms scan
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(1); }), 99 + 1 - 49);
}

TEST(Counters, PolarityInversionTurnsMaskIntoEnable) {
  HscCell cell("counters:\n  hsc0: {mode: MD0, mask: true, invert: [mask]}\n"
               "  sources:\n    - {name: gen, a: X0, hz: 10000}\n",
               kIdle);
  cell.run(10000, 1000);  // X2 = 0 with an inverted MASK: masked
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 0);
  cell.plc.set_input(2, true);  // enable from the scan at 10 ms on
  cell.run(11000, 1000);        // up to 20 ms: 10 ms at 10 kHz
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 100);
}

TEST(Counters, CountsStayExactAt460kHzWithCoarseScans) {
  // 460 kHz A/B x4 = 1.84 M counts/s with 10 ms scans: 18400 counts between two scans.
  HscCell cell("counters:\n  hsc0: {mode: MD7}\n  frequency_window: 100ms\n"
               "  sources:\n    - {name: enc, type: encoder, a: X0, hz: 460000}\n",
               kIdle);
  cell.run(3000000, 10000);
  cell.run(1, 1);  // one scan at exactly 3 s
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 5520000);
  EXPECT_DOUBLE_EQ(cell.with([](HscUnit& u) { return u.frequency(0); }), 1840000.0);
}

TEST(Counters, AnalyticCountForAnyFrequencyAndScanPeriod) {
  // A/B x4 counts = floor(4 * f * t) exactly, whatever the scan period.
  const double freqs[] = {1.0, 7.5, 999.999, 33333.333, 123456.789, 459999.999, 460000.0};
  const uint64_t periods_us[] = {1000, 3700, 10000};
  for (double f : freqs) {
    for (uint64_t p : periods_us) {
      HscCell cell("counters:\n  hsc0: {mode: MD7}\n  sources:\n    - {name: enc, type: encoder, a: X0, hz: " +
                       std::to_string(f) + "}\n",
                   kIdle);
      cell.run(1300000, p);
      const uint64_t last_ns = (cell.now_us - p) * 1000;
      const int64_t f_mhz = std::llround(f * 1000);
      const int64_t expect = static_cast<int64_t>((__int128(4) * f_mhz * last_ns) / 1000000000000ll);
      EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), expect) << f << " Hz, scan " << p << " us";
    }
  }
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
