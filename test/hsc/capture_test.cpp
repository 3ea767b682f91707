// Capture inputs (manual §9.7, spec §1.5): a pulse between two scans is seen ON
// for one scan; counting through a captured input needs a period > 2 scans.
#include <gtest/gtest.h>

#include <fstream>

#include "hsc_fixture.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {
namespace hsc {
namespace {

constexpr uint64_t kMs = 1000000;  // ns

TEST(Capture, PulseBetweenScansIsSeenForOneScan) {
  // A 0.3 ms pulse on X3 at 2.2 ms, 1 ms scans: sampled, no scan sees it.
  for (bool captured : {false, true}) {
    HscCell cell(captured ? "counters:\n  capture: [X3]\n" : "counters:\n  interrupts: []\n",
                 "ORG X3\nOUT Y0\nEND\n");
    cell.with([](HscUnit& u) {
      u.schedule_edge(3, 2200000, true);
      u.schedule_edge(3, 2500000, false);
      return 0;
    });
    cell.run(10000);
    const auto y0 = cell.changes_of(0);
    if (!captured) {
      EXPECT_TRUE(y0.empty());
      continue;
    }
    ASSERT_EQ(y0.size(), 2u);
    EXPECT_EQ(y0[0].t_ns, 3 * kMs);  // the scan after the pulse
    EXPECT_TRUE(y0[0].level);
    EXPECT_EQ(y0[1].t_ns, 4 * kMs);  // for one scan
  }
}

TEST(Capture, AnalyticSourceBetweenScans) {
  // 100 Hz pulses on X4 (ON [0,5) ms of every 10 ms); scans at 5, 15, 25 ... ms
  // always sample OFF. Captured, each scan after the first has seen an ON quarter.
  for (bool captured : {false, true}) {
    HscCell cell(std::string("counters:\n") + (captured ? "  capture: [X4]\n" : "") +
                     "  sources:\n    - {name: gen, a: X4, hz: 100}\n",
                 "ORG X4\nOUT Y0\nEND\n");
    cell.now_us = 5000;
    cell.run(100000, 10000);
    const auto y0 = cell.changes_of(0);
    if (!captured) {
      EXPECT_TRUE(y0.empty());
      continue;
    }
    ASSERT_EQ(y0.size(), 1u);  // ON at 15 ms and at every scan after
    EXPECT_EQ(y0[0].t_ns, 15 * kMs);
  }
}

// The manual's note: a 50 Hz input counted through a captured input needs scans
// shorter than 10 ms. X3 (exact edges) and X16 (sampled by the simulation) both carry
// a 50 Hz square wave, ON [20k+2, 20k+12) ms; X5 and X17 the same, not captured.
// A captured input is ON at a scan if it was ON at any instant since the last scan.
//  * 10 ms scans: every 10 ms interval holds an ON instant, so the captured inputs
//    are ON from the scan at 10 ms on: the CTR counts 1. (The plain samples at
//    20k+10 are ON, at 20k OFF: 50 counts, by luck of the phase.)
//  * 5 ms scans: the scan at 20k sees (20k-5, 20k] all OFF, the scan at 20k+5 the
//    pulse: one rising per pulse, k = 0..49 in 1 s: 50 counts.
uint32_t count_50hz(uint64_t scan_us, const std::string& counter) {
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/capture50.il") << "ORG X3\nCTR C0 30000\nORG X5\nCTR C1 30000\n"
                                          "ORG X16\nCTR C2 30000\nORG X17\nCTR C3 30000\nEND\n";
  const std::string wave = "{pulse: {period: 0.02, width: 0.01, delay: 0.002}}";
  std::ofstream(dir + "/capture50.yaml") << "cell: {program: capture50.il}\n"
                                            "simulation:\n  inputs:\n"
                                            "    X3: " << wave << "\n    X5: " << wave << "\n"
                                            "    X16: " << wave << "\n    X17: " << wave << "\n"
                                            "counters:\n  capture: [X3, X16]\n";
  SoftCell cell(dir + "/capture50.yaml", "");
  EXPECT_TRUE(cell.plc().set_mode(RunMode::Run));
  for (uint64_t t = 0; t < 1000000; t += scan_us) cell.plc().scan(t);
  return cell.plc().read(parse_address("R" + counter), 1).at(0);
}

TEST(Capture, FiftyHertzNeedsScansUnderTenMs) {
  EXPECT_EQ(count_50hz(10000, "C0"), 1u);   // captured, exact edges: pulses lost
  EXPECT_EQ(count_50hz(10000, "C2"), 1u);   // captured, sampled by the simulation
  EXPECT_EQ(count_50hz(10000, "C1"), 50u);  // plain samples
  EXPECT_EQ(count_50hz(5000, "C0"), 50u);   // every pulse
  EXPECT_EQ(count_50hz(5000, "C2"), 50u);
  EXPECT_EQ(count_50hz(5000, "C3"), 50u);
}

TEST(Capture, ShortPulsesThroughTheSimulation) {
  // 1 ms pulses every 20 ms at 10 ms scans on X16 (captured) and X17 (not): the
  // samples at 20k and 20k+10 ms never hit [20k+2, 20k+3).
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/capture_short.il") << "ORG X16\nCTR C0 30000\nORG X17\nCTR C1 30000\nEND\n";
  const std::string wave = "{pulse: {period: 0.02, width: 0.001, delay: 0.002}}";
  std::ofstream(dir + "/capture_short.yaml") << "cell: {program: capture_short.il}\n"
                                                "simulation:\n  inputs:\n"
                                                "    X16: " << wave << "\n    X17: " << wave << "\n"
                                                "counters:\n  capture: [X16]\n";
  SoftCell cell(dir + "/capture_short.yaml", "");
  ASSERT_TRUE(cell.plc().set_mode(RunMode::Run));
  for (uint64_t t = 0; t < 1000000; t += 10000) cell.plc().scan(t);
  EXPECT_EQ(cell.plc().read(parse_address("RC0"), 1).at(0), 50u);  // pulses k = 0..49, seen at 20k+10
  EXPECT_EQ(cell.plc().read(parse_address("RC1"), 1).at(0), 0u);
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
