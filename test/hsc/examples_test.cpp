// The manual's worked examples (§9.7, §10.5, §10.6) as IL programs in virtual time:
// the output timeline and the counts at which the ISRs ran.
#include "hsc_fixture.h"

namespace plc_cell {
namespace hsc {
namespace {

constexpr uint64_t kMs = 1000000;  // ns

// 10.5-2 Count-up stop: Y0 runs the motor until HSC0 reaches PV; the HSC0I routine
// stops it with an immediate output, so the count stops exactly at PV.
TEST(ManualExamples, CountUpStopAt460kHz) {
  HscCell cell(
      "counters:\n  hsc0: {mode: MD7}\n"
      "  sources:\n    - {name: enc, type: encoder, a: X0, hz: 460000, follow: Y0}\n",
      "ORG M1924\n"
      "FUN 8D MOV S=0 D=DR4096\n"
      "FUN 93 HSCTW CN=0 D=0\n"
      "FUN 8D MOV S=100000 D=DR4098\n"
      "FUN 93 HSCTW CN=0 D=1\n"
      "SET Y0\n"
      "ORG M1925\n"
      "FUN 92 HSCTR CN=0\n"
      "END\n"
      "LBL HSC0I\n"
      "ORG M1925\n"
      "RST Y0\n"
      "FUN 74 IMDIO D=Y0 N=1\n"
      "RTI\n");
  cell.run(100000, 1000);
  const auto y0 = cell.changes_of(0);
  ASSERT_EQ(y0.size(), 2u);
  EXPECT_EQ(y0[0].t_ns, 0u);
  EXPECT_TRUE(y0[0].level);
  // 100000 quarters at 1.84 M/s: 54.347826 ms, rounded up to the ns of the edge.
  EXPECT_EQ(y0[1].t_ns, 54347827u);
  EXPECT_FALSE(y0[1].level);
  ASSERT_EQ(cell.isrs.size(), 1u);
  EXPECT_EQ(cell.isrs[0].cv[0], 100000);
  EXPECT_EQ(cell.get("DR4096"), 100000u);  // no overshoot: the motor stopped at PV
}

// 10.5-1 Equal-length cutting: HSC0 A/B x4, PV advanced by the cut length DR0 in
// the ISR (CV never reset), cutter Y1 on for 0.1 s, X2 = material shortage.
TEST(ManualExamples, EqualLengthCutting) {
  HscCell cell(
      "counters:\n  hsc0: {mode: MD7}\n  interrupts: []\n"
      "  sources:\n    - {name: enc, type: encoder, a: X0, hz: 1000, follow: Y0}\n",
      "ORG M1924\n"
      "FUN 8D MOV S=1000 D=DR0\n"
      "FUN 8D MOV S=0 D=DR4096\n"
      "FUN 93 CN=0 D=0\n"
      "FUN 8D MOV S=DR0 D=DR4098\n"
      "FUN 93 CN=0 D=1\n"
      "ORG NOT X2\n"
      "OUT Y0\n"
      "ORG Y1\n"
      "TMR T1 10\n"
      "ORG T1\n"
      "RST Y1\n"
      "ORG M1925\n"
      "FUN 92 CN=0\n"
      "END\n"
      "LBL HSC0I\n"
      "ORG M1925\n"
      "SET Y1\n"
      "FUN 74 IMDIO D=Y1 N=1\n"
      "FUN 11D ADD Sa=DR4098 Sb=DR0 D=DR4098\n"
      "FUN 93 CN=0 D=1\n"
      "RTI\n");
  cell.with([](HscUnit& u) {
    u.schedule_edge(2, 1100 * kMs, true);  // material runs out at 1.1 s
    return 0;
  });
  cell.run(2000000, 1000);
  const auto cuts = cell.runs_of(kHsc0I);
  ASSERT_EQ(cuts.size(), 4u);
  for (size_t k = 0; k < cuts.size(); ++k) {
    EXPECT_EQ(cuts[k].t_ns, (k + 1) * 250 * kMs);  // 4000 counts/s, 1000 per cut
    EXPECT_EQ(cuts[k].cv[0], int64_t(1000 * (k + 1)));
  }
  const auto y1 = cell.changes_of(1);
  ASSERT_EQ(y1.size(), 8u);
  EXPECT_EQ(y1[0].t_ns, 250 * kMs);  // immediate output at the cut instant
  EXPECT_EQ(y1[1].t_ns, 350 * kMs);  // the 250 ms scan (after the ISR) starts T1: off 0.1 s later
  const auto y0 = cell.changes_of(0);
  ASSERT_EQ(y0.size(), 2u);
  EXPECT_EQ(y0[1].t_ns, 1100 * kMs);  // motor off at the scan that sees X2
  EXPECT_EQ(cell.get("DR4096"), 4400u);
}

// 10.6.3-2 RPM by the HSTA cyclic timer: HSC0 MD0 counts a photo-interrupter;
// every 10 pulses the ISR reads HSTA; RPM = 6000000 / dCV (0.1 ms units).
TEST(ManualExamples, RpmByCyclicTimer) {
  const std::pair<int, size_t> cases[] = {{600, 2}, {6000, 24}, {1500, 6}};  // ISRs in 2.5 s
  for (const auto& rc : cases) {
    const int rpm = rc.first;
    HscCell cell(
        "counters:\n  hsc0: {mode: MD0}\n"
        "  sources:\n    - {name: disk, a: X0, rpm: " + std::to_string(rpm) + ", per_rev: 1}\n",
        "ORG M1924\n"
        "FUN 8D MOV S=0 D=DR4096\n"
        "FUN 93 CN=0 D=0\n"
        "FUN 8D MOV S=10 D=DR4098\n"
        "FUN 93 CN=0 D=1\n"
        "FUN 8 MOV S=0 D=R4154\n"
        "FUN 93 CN=4 D=1\n"
        "FUN 92 CN=4\n"
        "FUN 8D MOV S=DR4152 D=DR2\n"
        "ORG M1\n"
        "FUN 14D DIV Sa=6000000 Sb=DR4 D=DR100\n"
        "RST M1\n"
        "END\n"
        "LBL HSC0I\n"
        "ORG M1925\n"
        "FUN 92 CN=4\n"
        "FUN 12D SUB Sa=DR4152 Sb=DR2 D=DR4\n"
        "FUN 8D MOV S=DR4152 D=DR2\n"
        "FUN 8D MOV S=0 D=DR4096\n"
        "FUN 93 CN=0 D=0\n"
        "SET M1\n"
        "RTI\n");
    cell.run(2500000, 1000);
    EXPECT_EQ(cell.get("DR4"), 6000000u / rpm) << rpm;
    EXPECT_EQ(cell.get("R100"), uint32_t(rpm)) << rpm;
    EXPECT_EQ(cell.runs_of(kHsc0I).size(), rc.second) << rpm;
  }
}

// 10.6.4-1 Drill-bit monitor: HST0 interrupts every 5 ms (PV advanced by 50);
// HSC1 (U on X4) counts the spindle: 18000 rpm x 8 pulses = 2400 Hz = 12 per 5 ms.
TEST(ManualExamples, DrillBitMonitor) {
  HscCell cell(
      "counters:\n  hsc0: {type: timer}\n  hsc1: {mode: MD0, a: X4}\n"
      "  sources:\n    - {name: spindle, a: X4, rpm: 18000, per_rev: 8}\n",
      "ORG M1924\n"
      "FUN 8D MOV S=0 D=DR4100\n"
      "FUN 93 CN=1 D=0\n"
      "FUN 8D MOV S=0 D=DR4096\n"
      "FUN 93 CN=0 D=0\n"
      "FUN 8D MOV S=50 D=DR4098\n"
      "FUN 93 CN=0 D=1\n"
      "END\n"
      "LBL HST0I\n"
      "ORG M1925\n"
      "FUN 92 CN=1\n"
      "FUN 12D SUB Sa=DR4100 Sb=DR10 D=DR0\n"
      "FUN 8D MOV S=DR4100 D=DR10\n"
      "FUN 11D ADD Sa=DR4098 Sb=50 D=DR4098\n"
      "FUN 93 CN=0 D=1\n"
      "FUN 17D CMP Sa=DR0 Sb=12 EQ=M10\n"
      "ORG NOT M10\n"
      "SET M11\n"
      "RTI\n");
  cell.run(1000000, 10000);  // 10 ms scans: two ISRs between scans
  const auto runs = cell.runs_of(kHsc0I);
  ASSERT_EQ(runs.size(), 198u);  // at 5, 10, ... 990 ms (the last scan is at 990 ms)
  for (size_t k = 0; k < runs.size(); ++k) ASSERT_EQ(runs[k].t_ns, (k + 1) * 5 * kMs);
  EXPECT_EQ(cell.get("DR0"), 12u);
  EXPECT_EQ(cell.get("M11"), 0u);  // every 5 ms window saw exactly 12 pulses
}

// 10.6.3-3 HSTA periodic: HSTAI every 0.5 ms compares HSC0 with R0 and turns Y0 on.
TEST(ManualExamples, HstaPeriodicCompare) {
  HscCell cell(
      "counters:\n  hsc0: {mode: MD7}\n"
      "  sources:\n    - {name: enc, type: encoder, a: X0, hz: 1000}\n",
      "ORG M1924\n"
      "FUN 8D MOV S=1001 D=DR0\n"
      "FUN 8 MOV S=5 D=R4154\n"
      "FUN 93 CN=4 D=1\n"
      "END\n"
      "LBL HSTAI\n"
      "ORG M1925\n"
      "FUN 92 CN=0\n"
      "FUN 17D CMP Sa=DR4096 Sb=DR0 LT=M20\n"
      "ORG NOT M20\n"
      "SET Y0\n"
      "FUN 74 IMDIO D=Y0 N=1\n"
      "RTI\n");
  cell.run(400000, 10000);
  // 1001 counts at 4000/s = 250.25 ms; the next HSTAI tick is at 250.5 ms.
  const auto y0 = cell.changes_of(0);
  ASSERT_EQ(y0.size(), 1u);
  EXPECT_EQ(y0[0].t_ns, 250500000u);
  EXPECT_EQ(cell.runs_of(kHstaI).size(), 780u);  // 0.5 .. 390 ms
}

// 10.6.4-3 HST3 periodic: DIS while M301; M300 starts HST3 with PV 5 and EN; the
// ISR resets CV so HST3I comes every 0.5 ms.
TEST(ManualExamples, Hst3PeriodicWithEnDis) {
  HscCell cell("counters:\n  hsc3: {type: timer}\n",
               "ORG M301\n"
               "FUN 146 DIS LBL=HST3I\n"
               "ORG TU M300\n"
               "FUN 8D MOV S=0 D=DR4108\n"
               "FUN 93 CN=3 D=0\n"
               "FUN 8D MOV S=5 D=DR4110\n"
               "FUN 93 CN=3 D=1\n"
               "FUN 145 EN LBL=HST3I\n"
               "END\n"
               "LBL HST3I\n"
               "ORG M1925\n"
               "FUN 15 INC D=R0\n"
               "FUN 8D MOV S=0 D=DR4108\n"
               "FUN 93 CN=3 D=0\n"
               "RTI\n");
  cell.run(10000, 1000);
  EXPECT_EQ(cell.get("R0"), 0u);
  cell.put("M300", 1);
  cell.run(100000, 1000);  // started at the 10 ms scan: ISRs at 10.5 ... 109.0 ms
  EXPECT_EQ(cell.get("R0"), 198u);
  cell.put("M301", 1);
  cell.run(10000, 1000);  // DIS at the 110 ms scan; 109.5 and 110.0 ms ran before it
  EXPECT_EQ(cell.get("R0"), 200u);
}

// 9-2: 1MSI with R4162 as the mask (M0 = 1 masks it). R0 +1 and R1 -1 per ms,
// between the 10 ms scans.
TEST(ManualExamples, OneMsTimeBaseWithR4162) {
  HscCell cell("",
               "ORG M0\n"
               "FUN 8 MOV S=255 D=R4162\n"
               "ORG NOT M0\n"
               "FUN 8 MOV S=0 D=R4162\n"
               "END\n"
               "LBL 1MSI\n"
               "ORG M1925\n"
               "FUN 15 INC D=R0\n"
               "FUN 16 DEC D=R1\n"
               "RTI\n");
  cell.run(100000, 10000);  // scans 0 .. 90 ms
  EXPECT_EQ(cell.get("R0"), 90u);
  EXPECT_EQ(static_cast<int16_t>(cell.get("R1")), -90);
  cell.put("M0", 1);
  cell.run(50000, 10000);  // the 100 ms scan masks it after the ticks up to 100 ms
  EXPECT_EQ(cell.get("R0"), 100u);
  cell.put("M0", 0);
  cell.run(50000, 10000);  // unmasked by the 150 ms scan: ticks 151 .. 190
  EXPECT_EQ(cell.get("R0"), 140u);
}

// 9-1 Precision position stop: X0 rising-edge interrupt stops the motor with an
// immediate output at the sensor's instant; without IMDIO it waits for the scan end.
TEST(ManualExamples, PrecisionStopOnInputEdge) {
  for (bool immediate : {true, false}) {
    HscCell cell("counters:\n  interrupts: [X0+]\n",
                 std::string("ORG M1924\nSET Y0\nEND\nLBL X0+I\nORG M1925\nRST Y0\n") +
                     (immediate ? "FUN 74 IMDIO D=Y0 N=1\n" : "") + "RTI\n");
    cell.with([](HscUnit& u) {
      u.schedule_edge(0, 12345600, true);
      return 0;
    });
    cell.run(20000, 1000);
    const auto y0 = cell.changes_of(0);
    ASSERT_EQ(y0.size(), 2u);
    EXPECT_EQ(y0[1].t_ns, immediate ? 12345600u : 13000000u);
  }
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
