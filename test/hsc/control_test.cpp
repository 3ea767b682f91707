// Software relays, EN/DIS, software-counter interrupts, timers read back, edge
// interrupts on analytic sources and the cell YAML's pulse signals as exact edges.
#include <fstream>

#include "hsc_fixture.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {
namespace hsc {
namespace {

constexpr uint64_t kMs = 1000000;  // ns

TEST(Control, SoftwareMaskAndClearRelaysActAtTheEndOfTheScan) {
  // HSC0 MD0 from a 1 kHz generator; M1940 (MASK) and M1941 (CLEAR) follow M10/M11.
  HscCell cell("counters:\n  hsc0: {mode: MD0}\n  sources:\n    - {name: gen, a: X0, hz: 1000}\n",
               "ORG M10\nOUT M1940\nORG M11\nOUT M1941\nEND\n");
  cell.run(10000);  // scans 0..9 ms: 9 pulses
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 9);
  cell.put("M10", 1);
  cell.run(10000);  // masked from the end of the 10 ms scan: the 10 ms pulse counted
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 10);
  cell.put("M10", 0);
  cell.put("M11", 1);
  cell.run(5000);  // cleared from the end of the 20 ms scan (which counted pulses 20 ms... masked)
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 0);
  cell.put("M11", 0);
  cell.run(5000);  // counting again after the 25 ms scan: 26 .. 29 ms
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 4);
}

TEST(Control, DisabledSoftwareCounterStopsHardwareCounterKeepsCounting) {
  // HSC0 (hardware) and HSC4 (software, on X4) count the same kind of generator;
  // both PVs are 5. DIS at the first scan: no interrupts; HSC4 does not count.
  HscCell cell(
      "counters:\n  hsc0: {mode: MD0}\n  hsc4: {mode: MD0, a: X4}\n"
      "  sources:\n    - {name: g0, a: X0, hz: 1000}\n    - {name: g4, a: X4, hz: 1000}\n",
      "ORG M1924\nFUN 8D MOV S=5 D=DR4098\nFUN 93 CN=0 D=1\nFUN 8D MOV S=5 D=DR4114\n"
      "ORG M1\nFUN 146 DIS LBL=HSC0I\nFUN 146 DIS LBL=HSC4I\nORG NOT M1\nFUN 145 EN LBL=HSC0I\n"
      "FUN 145 EN LBL=HSC4I\nEND\n"
      "LBL HSC0I\nORG M1925\nFUN 15 INC D=R0\nRTI\nLBL HSC4I\nORG M1925\nFUN 15 INC D=R4\nRTI\n");
  cell.put("M1", 1);
  cell.run(10000);
  EXPECT_EQ(cell.get("R0"), 0u);
  EXPECT_EQ(cell.get("R4"), 0u);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 9);  // 1..9 ms
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(4); }), 0);  // from the first scan on
  cell.put("M1", 0);
  cell.run(10000);  // EN at the 10 ms scan; HSC4 counts 11..19 -> reaches 5 at 15 ms
  EXPECT_EQ(cell.get("R4"), 1u);
  ASSERT_EQ(cell.runs_of(kHsc4I).size(), 1u);
  EXPECT_EQ(cell.runs_of(kHsc4I)[0].t_ns, 15 * kMs);
  EXPECT_EQ(cell.runs_of(kHsc4I)[0].cv[4], 5);
  EXPECT_EQ(cell.get("R0"), 0u);  // chip PV still 5: HSC0 passed it while disabled
}

TEST(Control, SoftwareCounterInterruptOnExplicitEdges) {
  HscCell cell("counters:\n  hsc7: {mode: MD2, a: X9, b: X10}\n",
               "ORG M1924\nFUN 8D MOV S=-2 D=DR4126\nEND\nLBL HSC7I\nORG M1925\nFUN 15 INC D=R0\nRTI\n");
  cell.with([](HscUnit& u) {
    u.schedule_edge(10, 500000, true);  // R = 1: count down
    for (int k = 0; k < 4; ++k) {
      u.schedule_edge(9, (k + 1) * kMs, true);
      u.schedule_edge(9, (k + 1) * kMs + 300000, false);
    }
    return 0;
  });
  cell.run(6000);
  EXPECT_EQ(static_cast<int32_t>(cell.get("DR4124")), -4);
  EXPECT_EQ(cell.get("R0"), 1u);
  ASSERT_EQ(cell.runs_of(kHsc4I + 3).size(), 1u);
  EXPECT_EQ(cell.runs_of(kHsc4I + 3)[0].t_ns, 2 * kMs);
}

TEST(Control, CyclicTimersReadBack) {
  // 10.6.3-1 HSTA cyclic and 10.6.4-2 HST3 cyclic (reset by M300's rising edge).
  HscCell cell("counters:\n  hsc3: {type: timer}\n",
               "ORG M1925\nFUN 92 CN=4\nFUN 92 CN=3\nORG TU M300\nFUN 8D MOV S=0 D=DR4108\nFUN 93 CN=3 D=0\nEND\n");
  cell.run(1234600, 100);  // 0.1 ms scans up to 1.2345 s
  EXPECT_EQ(cell.get("DR4152"), 12345u);
  EXPECT_EQ(cell.get("DR4108"), 12345u);
  cell.put("M300", 1);
  cell.run(5000, 100);  // reset at 1.2346 s; the last scan at 1.2395 s
  EXPECT_EQ(cell.get("DR4108"), 49u);
  EXPECT_EQ(cell.get("DR4152"), 12395u);
}

TEST(Control, EdgeInterruptOnAnAnalyticSourceRunsAtEachEdge) {
  // A 3 kHz photo-interrupter on X6 with X6+I: one routine per rising edge, at its ns.
  HscCell cell("counters:\n  interrupts: [X6+]\n  sources:\n    - {name: disk, a: X6, hz: 3000}\n",
               "ORG M1925\nOUT M0\nEND\nLBL X6+I\nORG M1925\nFUN 15 INC D=R0\nRTI\n");
  cell.run(10000, 1000);  // scans to 9 ms: edges at k/3000 s, k = 1..27
  EXPECT_EQ(cell.get("R0"), 27u);
  const auto runs = cell.runs_of(x_edge_source(6, false));
  ASSERT_EQ(runs.size(), 27u);
  EXPECT_EQ(runs[0].t_ns, 333334u);  // 1/3000 s, rounded up to the ns
  EXPECT_EQ(runs[2].t_ns, 1000000u);
}

TEST(Control, CellYamlPulseSignalsAreExactEdges) {
  // A 0.2 ms pulse every 0.7 ms on X4 with 1 ms scans: sampled at the scans most
  // pulses would be lost; as edges HSC4 counts every one.
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/pulse_cell.il") << "ORG M1925\nOUT M0\nEND\n";
  std::ofstream(dir + "/pulse_cell.yaml")
      << "cell: {program: pulse_cell.il}\n"
         "simulation:\n  inputs:\n    X4: {pulse: {period: 0.0007, width: 0.0002, delay: 0.0001}}\n"
         "counters:\n  hsc4: {mode: MD0, a: X4}\n";
  SoftCell cell(dir + "/pulse_cell.yaml", "");
  ASSERT_TRUE(cell.plc().set_mode(RunMode::Run));
  for (uint64_t t = 0; t <= 70000; t += 1000) cell.plc().scan(t);
  // Rising edges at 0.1 + 0.7k ms <= 70 ms: k = 0..99.
  EXPECT_EQ(cell.plc().locked([&](ScanEngine&, Memory&) { return cell.get<hsc::HscUnit>()->count(4); }), 100);
}

TEST(Control, APulseSignalFromTheFirstInstantIsOnAtTheFirstScan) {
  // delay 0 (the default): on for the first width already, as X20 (no counter input) is.
  // The rising edge at 0 is no edge "after" the start, and was lost: X4 read 0 at the
  // first scan and HSC4 missed the first pulse.
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/pulse0_cell.il") << "ORG M1925\nOUT M0\nEND\n";
  std::ofstream(dir + "/pulse0_cell.yaml")
      << "cell: {program: pulse0_cell.il}\n"
         "simulation:\n  inputs:\n    X4: {pulse: {period: 0.01, width: 0.005}}\n"
         "    X20: {pulse: {period: 0.01, width: 0.005}}\n"
         "counters:\n  hsc4: {mode: MD0, a: X4}\n";
  SoftCell cell(dir + "/pulse0_cell.yaml", "");
  ASSERT_TRUE(cell.plc().set_mode(RunMode::Run));
  const auto x = [&](int n) { return cell.plc().locked([&](ScanEngine&, Memory& m) { return m.bit(Area::X, n); }); };
  const auto count = [&] { return cell.plc().locked([&](ScanEngine&, Memory&) { return cell.get<hsc::HscUnit>()->count(4); }); };
  cell.plc().scan(0);
  EXPECT_EQ(x(4), 1) << "on from 0 to 5 ms";
  EXPECT_EQ(x(20), 1);
  EXPECT_EQ(count(), 1) << "the pulse from 0 ms";
  cell.plc().scan(5000);
  EXPECT_EQ(x(4), 0);
  EXPECT_EQ(x(20), 0);
  for (uint64_t t = 6000; t <= 100000; t += 1000) cell.plc().scan(t);
  // Rising edges at 10k ms <= 100 ms: k = 0..10.
  EXPECT_EQ(count(), 11);
}

TEST(Control, DoubleEdgeModesAndCountingInputInversion) {
  // MD1 (U/D x2) and MD3 (P/R x2, R = relay M1942 on: down) on a 1 kHz generator.
  for (int mode : {1, 3}) {
    HscCell cell("counters:\n  hsc0: {mode: MD" + std::to_string(mode) +
                     "}\n  sources:\n    - {name: gen, a: X0, hz: 1000}\n",
                 "ORG M1925\nOUT M1942\nEND\n");
    cell.run(1000000);
    cell.run(1);  // t = 1 s
    EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), mode == 1 ? 2000 : -2000) << mode;  // relay latched at t = 0, first edge at 0.5 ms
  }
  // Inverted counting input: MD0 counts the falling edges of the raw signal.
  HscCell inv("counters:\n  hsc0: {mode: MD0, invert: [count]}\n", "ORG M1925\nOUT M0\nEND\n");
  inv.with([](HscUnit& u) {
    u.schedule_edge(0, 1 * kMs, true);   // raw rise: inverted fall, no count
    u.schedule_edge(0, 2 * kMs, false);  // raw fall: counted
    u.schedule_edge(0, 3 * kMs, true);
    return 0;
  });
  inv.run(2500);
  EXPECT_EQ(inv.with([](HscUnit& u) { return u.count(0); }), 1);
  inv.run(1000);
  EXPECT_EQ(inv.with([](HscUnit& u) { return u.count(0); }), 1);
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
