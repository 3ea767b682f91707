// FUN72 TP4 and FUN85 TPSNS on the emulated FB-2A?4 / FB-4AJ(K)xx modules: the manual's
// examples, scaling rows 18-20 and 22 of the spec's table, the R4014 / R4004 timing,
// line-broken ALM, not-installed points and ERR on bad operands (virtual time).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fb_cell.h"
#include "plc_cell/temp/fb_modules.h"

namespace plc_cell {
namespace temp {
namespace {

// FUN72 program example 1 (B:460): an FB-2AK4 then an FB-2AJ4, both 0-10 V (Pl 0).
// The Ym figures are lost: Y16 and Y24 here.
const std::string kEx1Yaml = fb_yaml(R"(
      - type: 2AK4
        outputs: Y16
        polarity: unipolar
        channels: [{temperature: 350}, {temperature: 200}, {temperature: 25}, {open: true}]
      - type: 2AJ4
        outputs: Y24
        polarity: unipolar
        channels: [{temperature: 350}, {temperature: 100}, {temperature: 0}, {temperature: 700}]
)");
const char* kEx1Program =
    "ORG M0\nFUN 72 Tp=0 Pl=0 Sm=0 Ym=Y16 AR=R3842 TR=R0 WR=R100 ERR=M10 ALM=M1\n"
    "ORG M0\nFUN 72 Tp=1 Pl=0 Sm=4 Ym=Y24 AR=R3845 TR=R4 WR=R108 ERR=M11 ALM=M2\n"
    "ORG M0\nMOV S=R100 D=WM1000\n"
    "END\n";

TEST(Fun72, ManualExample1KThenJ) {
  FbCell c(kEx1Yaml, kEx1Program);
  c.set("M0", 1);
  c.run_to(1999000);  // R4014 default 500 ms per point: the 4th point is read at 2000 ms
  EXPECT_EQ(c.r("R3"), 0);
  c.run_to(2100000);
  // K, factor 248: 350 degC -> 350 x 1024 / 248 = 1445.2 -> AI 1445 - 2048 (unipolar) ->
  // primitive 1445 -> 1445 x 248 / 1024 = 349.96 -> 350. 200 -> 826 -> 200; 25 -> 103 -> 25.
  EXPECT_EQ(c.r("R0"), 350);
  EXPECT_EQ(c.r("R1"), 200);
  EXPECT_EQ(c.r("R2"), 25);
  EXPECT_EQ(c.r("R3968"), 1445);
  EXPECT_EQ(c.r("R3969"), 826);
  EXPECT_EQ(c.r("R3970"), 103);
  // The open 4th point: AI 2047 -> primitive 4095 -> 991.8 -> 992 > 900: line broken.
  EXPECT_EQ(c.r("R3"), 992);
  EXPECT_EQ(c.r("R3971"), 4095);
  EXPECT_EQ(c.r("R100"), 0b1000);
  EXPECT_EQ(c.r("M1000"), 0);
  EXPECT_EQ(c.r("M1003"), 1);
  EXPECT_EQ(c.r("M1"), 1);
  // J, factor 240: 350 -> 1493 -> 349.9 -> 350; 100 -> 427 -> 100.1 -> 100; 0 -> 0; 700 -> 2987 -> 700.
  EXPECT_EQ(c.r("R4"), 350);
  EXPECT_EQ(c.r("R5"), 100);
  EXPECT_EQ(c.r("R6"), 0);
  EXPECT_EQ(c.r("R7"), 700);
  EXPECT_EQ(c.r("R3972"), 1493);
  EXPECT_EQ(c.r("R3975"), 2987);
  EXPECT_EQ(c.r("M2"), 0);
  EXPECT_EQ(c.r("M10"), 0);
  EXPECT_EQ(c.r("M11"), 0);
  // EN off: the multiplexing DO go off, the readings stay.
  c.set("M0", 0);
  c.run_to(2200000);
  EXPECT_EQ(c.r("Y16") + c.r("Y17") + c.r("Y24") + c.r("Y25"), 0);
  EXPECT_EQ(c.r("R0"), 350);
}

TEST(Fun72, NotInstalledPointReadsZeroWithoutAlarm) {
  FbCell c(kEx1Yaml, kEx1Program);
  c.set("M0", 1);
  c.run_to(1000);
  c.set("R4010", 0xFFF7);  // point 4 (the open one) not installed
  c.run_to(2100000);
  EXPECT_EQ(c.r("R3"), 0);
  EXPECT_EQ(c.r("R100"), 0);
  EXPECT_EQ(c.r("M1"), 0);
  EXPECT_EQ(c.r("R0"), 350);  // the others as before
}

TEST(Fun72, IrCeilingRows18And19) {
  // 950 degC: unipolar 10 V gives AI 1875 -> held at 1842 -> primitive 3890 -> 942 > 900:
  // line broken (row 19). Bipolar 10 V: 950 x 1024 / 496 = 1961 -> 1842 -> 892 < 900 (row 18).
  const std::string yaml = fb_yaml(R"(
      - {type: 2AK4, outputs: Y16, polarity: unipolar, channels: [{temperature: 950}]}
      - {type: 2AK4, outputs: Y24, polarity: bipolar, channels: [{temperature: 950}]}
)");
  FbCell c(yaml,
           "ORG M0\nFUN 72 Tp=0 Pl=0 Sm=0 Ym=Y16 AR=R3842 TR=R0 WR=R100 ALM=M1\n"
           "ORG M0\nFUN 72 Tp=0 Pl=2 Sm=4 Ym=Y24 AR=R3845 TR=R4 WR=R108 ALM=M2\nEND\n");
  c.set("M0", 1);
  c.run_to(600000);
  EXPECT_EQ(c.r("R3968"), 3890);
  EXPECT_EQ(c.r("R0"), 942);
  EXPECT_EQ(c.r("M1"), 1);
  EXPECT_EQ(c.r("R3972"), 1842);
  EXPECT_EQ(c.r("R4"), 892);
  EXPECT_EQ(c.r("R108") & 1, 0);
}

TEST(Fun72, FiveVoltSpanHalvesR4016) {
  // plc_cell's choice: FUN72 on a 5 V span uses R4016 / 2 (FUN85's default 124 = 248 / 2).
  // +-5 V K at 242.19 degC: 242.19 x 1024 / (2 x 124) = 1000 counts; 1000 x 2 x 124 / 1024 = 242.2 -> 242.
  const std::string yaml = fb_yaml(R"(
      - {type: 2AK4, outputs: Y16, span: 5, channels: [{temperature: 242.19}, {temperature: -50}]}
)");
  FbCell c(yaml, "ORG M0\nFUN 72 Tp=0 Pl=3 Sm=0 Ym=Y16 AR=R3842 TR=R0 WR=R100 ALM=M1\nEND\n");
  c.set("M0", 1);
  c.run_to(1100000);
  EXPECT_EQ(c.r("R3968"), 1000);
  EXPECT_EQ(c.r("R0"), 242);
  // Negative, +-5 V: -50 x 1024 / 286 = -179.0 -> -179 x 286 / 1024 = -49.99 -> -50.
  EXPECT_EQ(c.r("R3969"), -179);
  EXPECT_EQ(c.r("R1"), -50);
}

TEST(Fun72, Pt100OnAnFb2AH4) {
  // PT-100 DIN, +-10 V (Pl 2), 100.0 degC: reads 1000 (0.1 degC); the primitive is the
  // reading over the span -49.8..146.6 degC as 0..4095: (1000 + 498) / 1964 x 4095 = 3123.4.
  const std::string yaml = fb_yaml(R"(
      - {type: 2AH4, outputs: Y16, channels: [{temperature: 100}, {temperature: -20.5}, {open: true}]}
)");
  FbCell c(yaml, "ORG M0\nFUN 72 Tp=2 Pl=2 Sm=0 Ym=Y16 AR=R3842 TR=R0 WR=R100 ALM=M1\nEND\n");
  c.set("M0", 1);
  c.run_to(2100000);
  // One AI count is 196.4 / 3890 = 0.05 degC, so the round trip is within 0.1 degC.
  EXPECT_NEAR(c.r("R0"), 1000, 1);
  EXPECT_NEAR(c.r("R3968"), 3123, 2);
  EXPECT_NEAR(c.r("R1"), -205, 1);
  // Open: above the ceiling -> 999.9 degC > 900.0: line broken, primitive 4095.
  EXPECT_EQ(c.r("R2"), 9999);
  EXPECT_EQ(c.r("R3970"), 4095);
  EXPECT_EQ(c.r("R100"), 0b1100);  // the unwired 4th point reads open too
  EXPECT_EQ(c.r("M1"), 1);
}

// The ms between the last two of three completed multiplex cycles (WR+3 counts them).
uint64_t cycle_ms(FbCell& c, const char* wr3) {
  std::vector<uint64_t> at;
  for (int last = c.r(wr3); at.size() < 3; c.run_to(c.now))
    if (c.r(wr3) != last) at.push_back(c.now - 1000), last = c.r(wr3);
  return (at[2] - at[1]) / 1000;
}

TEST(Fun72, UpdatePeriodIsR4014TimesFour) {
  // Spec row 21: 500 / 250 / 1000 / 2000 ms per point -> an update every 2 / 1 / 4 / 8 s.
  for (const auto& [slot, period] : std::vector<std::pair<int, uint64_t>>{{500, 2000}, {250, 1000}, {1000, 4000}, {2000, 8000}}) {
    FbCell c(kEx1Yaml, "ORG M0\nFUN 72 Tp=0 Pl=0 Sm=0 Ym=Y16 AR=R3842 TR=R0 WR=R100\nEND\n");
    c.run_to(0);
    c.set("R4014", uint32_t(slot));
    c.set("M0", 1);
    EXPECT_EQ(cycle_ms(c, "R103"), period) << "R4014 = " << slot;
  }
}

TEST(Fun72, ErrOnBadTpPlSmAndNothingWritten) {
  for (const char* ops : {"Tp=4 Pl=0 Sm=0", "Tp=0 Pl=4 Sm=0", "Tp=0 Pl=0 Sm=3", "Tp=0 Pl=0 Sm=32",
                          "Tp=2 Pl=0 Sm=0" /* an RTD is bipolar only */}) {
    FbCell c(kEx1Yaml, std::string("ORG M0\nFUN 72 ") + ops + " Ym=Y16 AR=R3842 TR=R0 WR=R100 ERR=M10 ALM=M1\nEND\n");
    c.set("R0", 1234);
    c.set("M0", 1);
    c.run_to(2100000);
    EXPECT_EQ(c.r("M10"), 1) << ops;
    EXPECT_EQ(c.r("R0"), 1234) << ops;
    EXPECT_EQ(c.r("R3968"), 0) << ops;
    EXPECT_EQ(c.r("Y16"), 0) << ops;
  }
}

TEST(Fun72, SkippedScanRestartsTheCycle) {
  // "must be executed every scan": a scan that jumps over it loses the point being
  // converted and the cycle starts again at point 0.
  FbCell c(kEx1Yaml, "ORG M5\nJMP skip\nORG M0\nFUN 72 Tp=0 Pl=0 Sm=0 Ym=Y16 AR=R3842 TR=R0 WR=R100\n"
                     "LBL skip\nEND\n");
  c.set("M0", 1);
  c.run_to(1200000);
  EXPECT_EQ(c.r("R102"), 2);  // WR+2: point 2 selected (points 0 and 1 read at 500, 1000 ms)
  c.set("M5", 1);
  c.run_to(1201000);  // one scan without FUN72
  c.set("M5", 0);
  c.run_to(1202000);
  EXPECT_EQ(c.r("R102"), 0);  // back at point 0
  c.run_to(3202000);  // a full cycle (4 x 500 ms) from 1202 ms
  EXPECT_EQ(c.r("R103"), 1);  // WR+3: the first complete cycle
  EXPECT_EQ(c.r("R3"), 992);
}

TEST(Fun72, MovingAverageOfR4015Samples) {
  // A zone at 100 degC heading for 500 degC with tau 100 s: T(t) = 500 - 400 exp(-t / 100 s).
  // Point 0 is converted at 0.5 s + 2 s k; with R4015 = 2 (4 samples) the reading is the
  // rounded mean of the last 4 primitives round(T x 1024 / 248), times 248 / 1024.
  const std::string yaml = fb_yaml(R"(
      - {type: 2AK4, outputs: Y16, polarity: unipolar, channels: [{plant: p}]}
  plants:
    - {name: p, ambient: 500, initial: 100, gain: 0, time_constant: 100, dead_time: 0}
)");
  FbCell c(yaml, "ORG M0\nFUN 72 Tp=0 Pl=0 Sm=0 Ym=Y16 AR=R3842 TR=R0 WR=R100\nEND\n");
  c.run_to(0);
  c.set("R4015", 2);
  c.set("M0", 1);
  c.run_to(12000000);  // samples at 0.5, 2.5 .. 10.5 s: the last four are 4.5 .. 10.5 s
  double sum = 0;
  // FUN72 starts at the 1 ms scan: the samples are 1 ms later.
  for (double t : {4.501, 6.501, 8.501, 10.501}) sum += std::round((500 - 400 * std::exp(-t / 100)) * 1024 / 248);
  const double mean = std::round(sum / 4);
  EXPECT_EQ(c.r("R3968"), mean);
  EXPECT_EQ(c.r("R0"), std::lround(mean * 248 / 1024));
  // Without averaging the reading is the last sample's, 10.5 s: 139.87 degC -> 140; the mean lags.
  EXPECT_LT(c.r("R0"), 140);
}

// FUN85 example (B:917): FBx-28MC with an FB-4AK24 at 0-10 V, Zn 24 -> R0-R23, primitives
// R3968-R3991, line broken in WR+0/WR+1 -> M1000-M1023. The Yn figure is lost: Y16.
const std::string k4akYaml = fb_yaml(R"(
      - type: 4AK24
        outputs: Y16
        polarity: unipolar
        channels: [{temperature: 100}, {temperature: 200}, {temperature: 300}, {temperature: 400},
                   {temperature: 500}, {temperature: 600}, {temperature: 25}, {temperature: 50},
                   {temperature: 75}, {temperature: 125}, {temperature: 150}, {temperature: 175},
                   {temperature: 225}, {temperature: 250}, {temperature: 275}, {temperature: 325},
                   {temperature: 350}, {open: true}, {temperature: 375}, {temperature: 425},
                   {temperature: 450}, {temperature: 475}, {temperature: 525}, {temperature: 550}]
)");
const char* kFun85Program = "ORG M0\nFUN 85 Tp=0 Pl=0 Zn=24 Yn=Y16 SR=R0 WR=R100 ERR=M10 ALM=M1\n"
                            "ORG M0\nMOV.D S=R100 D=WM1000\nEND\n";

TEST(Fun85, ManualExampleFb4AK24) {
  FbCell c(k4akYaml, kFun85Program);
  c.set("M0", 1);
  c.run_to(2100000);  // R4004 default 333 ms x 6 points = 1998 ms
  // R4000-R4004 initialised for K, 0-10 V (B:878-B:913).
  EXPECT_EQ(c.r("R4001"), 248);
  EXPECT_EQ(c.r("R4002"), 286);
  EXPECT_EQ(c.r("R4003"), 901);
  EXPECT_EQ(c.r("R4004"), 333);
  // 100 degC -> 100 x 1024 / 248 = 412.9 -> 413 -> 100.02 -> 100 ... (each to 1 degC).
  const int expect[24] = {100, 200, 300, 400, 500, 600, 25, 50, 75, 125, 150, 175,
                          225, 250, 275, 325, 350, 992, 375, 425, 450, 475, 525, 550};
  for (int i = 0; i < 24; ++i) {
    const std::string a = "R" + std::to_string(i);
    EXPECT_EQ(c.r(a.c_str()), expect[i]) << a;
  }
  EXPECT_EQ(c.r("R3968"), 413);
  EXPECT_EQ(c.r("R101"), 0b10);  // point 18 (the open one): WR+1 bit 1
  EXPECT_EQ(c.r("M1017"), 1);
  EXPECT_EQ(c.r("M1"), 1);
  EXPECT_EQ(c.r("M10"), 0);
}

TEST(Fun85, R4001FiveVoltRow20) {
  // Row 20: FUN85, K, +-5 V: R4001 defaults to 124; primitive 1000 -> 1000 x 2 x 124 / 1024 = 242.2.
  const std::string yaml = fb_yaml(R"(
      - {type: 4AK12, outputs: Y16, span: 5, channels: [{temperature: 242.19}]}
)");
  FbCell c(yaml, "ORG M0\nFUN 85 Tp=0 Pl=3 Zn=12 Yn=Y16 SR=R0 WR=R100 ALM=M1\nEND\n");
  c.set("M0", 1);
  c.run_to(2100000);
  EXPECT_EQ(c.r("R4001"), 124);
  EXPECT_EQ(c.r("R4003"), 451);
  EXPECT_EQ(c.r("R3968"), 1000);
  EXPECT_EQ(c.r("R0"), 242);
}

TEST(Fun85, UpdatePeriodIsR4004TimesSix) {
  // Spec row 22: 333 / 166 / 666 / 1333 ms per point -> 1998 / 996 / 3996 / 7998 ms.
  for (const auto& [slot, period] : std::vector<std::pair<int, uint64_t>>{{333, 1998}, {166, 996}, {666, 3996}, {1333, 7998}}) {
    FbCell c(k4akYaml, kFun85Program);
    c.set("M0", 1);
    c.run_to(0);  // the first execution initialises R4000-R4004; then the program's value
    c.set("R4004", uint32_t(slot));
    EXPECT_EQ(cycle_ms(c, "R103"), period) << "R4004 = " << slot;
  }
}

TEST(Fun85, LineBrokenThresholdIsR4003) {
  FbCell c(k4akYaml, kFun85Program);
  c.set("M0", 1);
  c.run_to(0);
  c.set("R4003", 500);  // the program's threshold: 500 degC and above read line-broken
  c.run_to(2100000);
  // 500 degC -> 2065 -> 500.1 -> 500 (point 5), 600 (6); 992 (18, open), 525 (23), 550 (24).
  EXPECT_EQ(c.r("R100"), 0b110000);
  EXPECT_EQ(c.r("R101"), 0b11000010);
}

TEST(Fun85, ErrOnBadOperandsAndOnlyOnce) {
  for (const char* ops : {"Tp=2 Pl=0 Zn=24", "Tp=0 Pl=5 Zn=24", "Tp=0 Pl=0 Zn=25", "Tp=0 Pl=0 Zn=0"}) {
    FbCell c(k4akYaml, std::string("ORG M0\nFUN 85 ") + ops + " Yn=Y16 SR=R0 WR=R100 ERR=M10\nEND\n");
    c.set("M0", 1);
    c.run_to(2100000);
    EXPECT_EQ(c.r("M10"), 1) << ops;
    EXPECT_EQ(c.r("R0"), 0) << ops;
  }
  FbCell twice(k4akYaml, "ORG M0\nFUN 85 Tp=0 Pl=0 Zn=24 Yn=Y16 SR=R0 WR=R100 ERR=M10\n"
                         "ORG M0\nFUN 85 Tp=0 Pl=0 Zn=6 Yn=Y16 SR=R200 WR=R300 ERR=M11\nEND\n");
  twice.set("M0", 1);
  twice.run_to(2100000);
  EXPECT_EQ(twice.r("M10"), 0);
  EXPECT_EQ(twice.r("M11"), 1);  // "can only be used once"
  EXPECT_EQ(twice.r("R200"), 0);
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
