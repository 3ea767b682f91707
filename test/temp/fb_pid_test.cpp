// FUN73 TSTC (the manual's example 1: 4 x FB-2AK4, one FUN73 over 16 points) and the FB
// FUN86 TPCTL with FUN85 settling a simulated zone, in virtual time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fb_cell.h"

namespace plc_cell {
namespace temp {
namespace {

// FUN73 program example 1 (B:713-B:780), 0-10 V. Point temperatures are fixed: 200 degC
// on points 1-15 and 350 on point 16 (out of the 195..205 zone).
const std::string kEx1Yaml = fb_yaml(R"(
      - {type: 2AK4, outputs: Y16, polarity: unipolar, channels: [{temperature: 200}, {temperature: 200}, {temperature: 200}, {temperature: 200}]}
      - {type: 2AK4, outputs: Y24, polarity: unipolar, channels: [{temperature: 200}, {temperature: 200}, {temperature: 200}, {temperature: 200}]}
      - {type: 2AK4, outputs: Y32, polarity: unipolar, channels: [{temperature: 200}, {temperature: 200}, {temperature: 200}, {temperature: 200}]}
      - {type: 2AK4, outputs: Y40, polarity: unipolar, channels: [{temperature: 200}, {temperature: 200}, {temperature: 190}, {temperature: 350}]}
)");
const char* kEx1Program =
    "ORG M1924\nMOV.D S=WM800 D=R4010\nMOV.D S=WM832 D=R4012\n"
    "ORG M3\nFUN 72 Tp=0 Pl=0 Sm=12 Ym=Y40 AR=R3851 TR=R12 WR=R240\n"
    "ORG M3\nFUN 72 Tp=0 Pl=0 Sm=8 Ym=Y32 AR=R3848 TR=R8 WR=R230\n"
    "ORG M3\nFUN 72 Tp=0 Pl=0 Sm=4 Ym=Y24 AR=R3845 TR=R4 WR=R220\n"
    "ORG M3\nLD M1925\n"
    "FUN 73 Tp=0 Pl=0 Sm=0 Ym=Y16 AR=R3842 TR=R0 Yh=Y48 Sh=0 Zh=16 Sv=R100 Os=R120 PR=R140 IR=R160 DR=R180 "
    "OR=R300 WR=R200 ERR=M10 AO0=M11 AO1=M12\n"
    "ORG M3\nMOV S=R210 D=WM1016\nMOV S=R208 D=WM1032\n"
    "END\n";

TEST(Fun73, ManualExample1SixteenPoints) {
  FbCell c(kEx1Yaml, kEx1Program);
  c.set("M3", 1);
  c.run_to(0);
  c.set("R4010", 0xFFFF), c.set("R4011", 0xFFFF), c.set("R4012", 0xFFFF), c.set("R4013", 0xFFFF);  // WM800/WM832
  for (uint32_t i = 0; i < 16; ++i) c.p.write(Address{Area::R, Width::Word, 100 + i}, {200}), c.p.write(Address{Area::R, Width::Word, 120 + i}, {5});
  c.run_to(2100000);
  EXPECT_EQ(c.r("M10"), 0);
  EXPECT_EQ(c.r("R0"), 200);
  EXPECT_EQ(c.r("R14"), 190);
  EXPECT_EQ(c.r("R15"), 350);
  // Defaults on the first execution: Kc 60 (0-10 V), Ti 17, Td 100 (B:655).
  EXPECT_EQ(c.r("R140"), 60);
  EXPECT_EQ(c.r("R175"), 17);
  EXPECT_EQ(c.r("R195"), 100);
  // In zone 195..205 (row 23): points 1-14 yes, 15 (190) and 16 (350) no -> M1032-M1047.
  EXPECT_EQ(uint16_t(c.r("R208")), 0x3FFF);
  EXPECT_EQ(c.r("M1045"), 1);  // point 14
  EXPECT_EQ(c.r("M1046"), 0);  // point 15
  EXPECT_EQ(c.r("M12"), 1);  // AO1: out of zone
  // Point 15, 10 degC below: error in counts = round(200 x 1024 / 248) - round(190 x 1024 / 248)
  // = 826 - 785 = 41; the first solve adds one integral step: 60 x 41 x (1 + 17 x 20 / 60000) = 2473.9.
  EXPECT_EQ(c.r("R314"), 2474);
  EXPECT_EQ(c.r("R315"), 0);  // 350: far above, heating off
  EXPECT_EQ(c.r("Y62"), 1);   // PWM: duty 2474 / 4095 of the 2 s cycle, on at its start
  EXPECT_EQ(c.r("Y63"), 0);
  c.run_to(3200000);  // on for 0.604 x 2 s = 1.208 s after the cycle start at 2.0 s
  EXPECT_EQ(c.r("Y62"), 1);
  c.run_to(3300000);
  EXPECT_EQ(c.r("Y62"), 0);
  // High temperature: R4008 (1 degree, default 350) reached on ten executions -> WR+10.
  EXPECT_EQ(uint16_t(c.r("R210")), 0x8000);
  EXPECT_EQ(c.r("M1031"), 1);
}

TEST(Fun73, ErrOnShBelowSm) {
  // Zh > 4 needs Sh >= Sm (B:757): ERR on, nothing written.
  FbCell c(kEx1Yaml, "ORG M3\nLD M1925\nFUN 73 Tp=0 Pl=0 Sm=4 Ym=Y16 AR=R3842 TR=R0 Yh=Y48 Sh=0 Zh=8 "
                     "Sv=R100 Os=R120 PR=R140 IR=R160 DR=R180 OR=R300 WR=R200 ERR=M10\nEND\n");
  c.set("M3", 1);
  c.run_to(2100000);
  EXPECT_EQ(c.r("M10"), 1);
  EXPECT_EQ(c.r("R140"), 0);
  EXPECT_EQ(c.r("R0"), 0);
}

// FUN73 program example 2 (B:782-B:830): four FB-2AH4 (PT-100, DIN) on the 5 V span,
// bipolar (fixed), Tp=2 Pl=3, three FUN72 and one FUN73 over the 16 points. The page
// also says "only ... while the sensor is the thermocouple" (B:686); plc_cell follows the
// example (docs/analog-and-temperature.md, "FUN73 on an RTD"). Points 1-14 at 50.0 degC,
// point 15 at 49.8, point 16 at 80.0; set points 50.0 degC, zone +-0.5.
const std::string kEx2Yaml = fb_yaml(R"(
      - {type: 2AH4, outputs: Y16, span: 5, channels: [{temperature: 50}, {temperature: 50}, {temperature: 50}, {temperature: 50}]}
      - {type: 2AH4, outputs: Y24, span: 5, channels: [{temperature: 50}, {temperature: 50}, {temperature: 50}, {temperature: 50}]}
      - {type: 2AH4, outputs: Y32, span: 5, channels: [{temperature: 50}, {temperature: 50}, {temperature: 50}, {temperature: 50}]}
      - {type: 2AH4, outputs: Y40, span: 5, channels: [{temperature: 50}, {temperature: 50}, {temperature: 49.8}, {temperature: 80}]}
)");
const char* kEx2Program =
    "ORG M1924\nMOV.D S=WM800 D=R4010\nMOV.D S=WM832 D=R4012\n"
    "ORG M3\nFUN 72 Tp=2 Pl=3 Sm=12 Ym=Y40 AR=R3851 TR=R12 WR=R240\n"
    "ORG M3\nFUN 72 Tp=2 Pl=3 Sm=8 Ym=Y32 AR=R3848 TR=R8 WR=R230\n"
    "ORG M3\nFUN 72 Tp=2 Pl=3 Sm=4 Ym=Y24 AR=R3845 TR=R4 WR=R220\n"
    "ORG M3\nLD M1925\n"
    "FUN 73 Tp=2 Pl=3 Sm=0 Ym=Y16 AR=R3842 TR=R0 Yh=Y48 Sh=0 Zh=16 Sv=R100 Os=R120 PR=R140 IR=R160 DR=R180 "
    "OR=R300 WR=R200 ERR=M10 AO0=M11 AO1=M12\n"
    "END\n";

TEST(Fun73, ManualExample2Pt100) {
  FbCell c(kEx2Yaml, kEx2Program);
  c.set("M3", 1);
  c.run_to(0);
  c.set("R4010", 0xFFFF), c.set("R4011", 0xFFFF), c.set("R4012", 0xFFFF), c.set("R4013", 0xFFFF);
  for (uint32_t i = 0; i < 16; ++i)
    c.p.write(Address{Area::R, Width::Word, 100 + i}, {500}), c.p.write(Address{Area::R, Width::Word, 120 + i}, {5});
  c.run_to(2100000);
  EXPECT_EQ(c.r("M10"), 0);  // no ERR: FUN73 takes the RTD
  EXPECT_EQ(c.r("M11"), 0);  // no line broken
  // The measurement, in 0.1 degC (R4022 = 1024), and the primitives 0..4095 over the 5 V
  // span's -12.3..83.6 degC: (498 + 123) / 959 x 4095 = 2651.7.
  EXPECT_EQ(c.r("R0"), 500);
  EXPECT_EQ(c.r("R14"), 498);
  EXPECT_EQ(c.r("R15"), 800);
  EXPECT_EQ(c.r("R3982"), 2652);
  // Defaults: Kc 60 for -5..5 V (Pl 3), Ti 17, Td 100.
  EXPECT_EQ(c.r("R140"), 60);
  EXPECT_EQ(c.r("R160"), 17);
  EXPECT_EQ(c.r("R180"), 100);
  // In zone 49.5..50.5 degC: points 1-15, not 16 -> WR+8; AO1 for point 16.
  EXPECT_EQ(uint16_t(c.r("R208")), 0x7FFF);
  EXPECT_EQ(c.r("M12"), 1);
  // Point 15: the set point in the same counts, (500 + 123) / 959 x 4095 = 2660.2 -> 2660;
  // error 2660 - 2652 = 8; the first solve: 60 x 8 x (1 + 17 x 20 / 60000) = 482.7.
  EXPECT_EQ(c.r("R314"), 483);
  EXPECT_EQ(c.r("R300"), 0);   // at the set point: no error, no output
  EXPECT_EQ(c.r("R315"), 0);   // 80.0 degC: far above, heating off
  EXPECT_EQ(c.r("Y62"), 1);    // PWM: 483 / 4095 of the 2 s cycle, on at its start
  c.run_to(2300000);           // 0.236 s after the cycle start at 2.0 s
  EXPECT_EQ(c.r("Y62"), 0);
  // R4008 is in degrees (default 350): 80.0 degC is no high-temperature warning...
  c.run_to(30000000);
  EXPECT_EQ(uint16_t(c.r("R210")), 0);
  // ...until R4008 is 60 degC: ten executions at 80.0 degC >= 60 -> WR+10 bit 15.
  c.set("R4008", 60);
  c.run_to(30020000);
  EXPECT_EQ(uint16_t(c.r("R210")), 0x8000);
}

// The FB FUN86 with FUN85 on an FB-4AK12 (0-10 V), heating an oven (gain 300 degC, tau
// 600 s, dead time 10 s) through Y30 from 25 to 200 degC.
const std::string kOvenYaml = fb_yaml(R"(
      - {type: 4AK12, outputs: Y16, polarity: unipolar, channels: [{name: oven, plant: oven}]}
  plants:
    - {name: oven, ambient: 25, initial: 25, gain: 300, time_constant: 600, dead_time: 10, heater: Y30}
)");
const char* kOvenProgram =
    "ORG M1924\nMOV S=200 D=R100\nMOV S=1 D=R120\n"   // SV 200 degC, zone +-1
    "MOV S=40 D=R140\nMOV S=20 D=R160\nMOV S=10 D=R180\n"  // Kc 40, Ti 0.2 rep/min, Td 0.1 min
    "ORG M0\nFUN 85 Tp=0 Pl=0 Zn=12 Yn=Y16 SR=R0 WR=R50 ERR=M1\n"
    "ORG M0\nLD M1925\n"
    "FUN 86 Yn=Y30 Sn=0 Zn=1 Sv=R100 Os=R120 PR=R140 IR=R160 DR=R180 OR=R200 WR=R220 ERR=M2 ALM=M3\n"
    "END\n";

TEST(Fun86Fb, OvenSettlesAt200) {
  FbCell c(kOvenYaml, kOvenProgram);
  c.set("M0", 1);
  double peak = 0, reached = -1, worst = 0;
  const uint64_t scan = 10000;
  for (uint64_t t = 0; t <= 3600ull * 1000000; t += scan) {
    c.run_to(t, scan);
    const double temp = c.cell->plant("oven")->temperature_c();
    peak = std::max(peak, temp);
    if (reached < 0 && temp >= 199.5) reached = t / 1e6;
    if (reached >= 0 && t > reached * 1e6 + 600e6) worst = std::max(worst, std::fabs(temp - 200.0));
  }
  EXPECT_EQ(c.r("M1"), 0);
  EXPECT_EQ(c.r("M2"), 0);
  ASSERT_GT(reached, 0);
  EXPECT_LT(reached, 1800);
  EXPECT_LT(peak, 205.0);
  // The FB reading has 1 degC resolution (one primitive count is 0.24 degC): held within 1.5 degC.
  EXPECT_LT(worst, 1.5);
  EXPECT_NEAR(c.r("R0"), 200, 1);
  EXPECT_EQ(c.r("R220") & 1, 1);  // in zone
  EXPECT_EQ(c.r("R224"), 20);     // Ts 2 s (R4005 default 0, FB codes)
}

TEST(Fun86Fb, OffUntilFun85HasReadEveryPoint) {
  FbCell c(kOvenYaml, kOvenProgram);
  c.set("M0", 1);
  c.run_to(1900000);  // 6 x 333 ms = 1998 ms: not yet
  EXPECT_EQ(c.r("R200"), 0);
  EXPECT_EQ(c.r("Y30"), 0);
  c.run_to(2100000);
  EXPECT_GT(c.r("R200"), 0);
  EXPECT_EQ(c.r("Y30"), 1);
  EXPECT_EQ(c.r("M2"), 0);
}

TEST(Fun86Fb, ErrOnBadSnZn) {
  FbCell c(kOvenYaml, "ORG M0\nFUN 85 Tp=0 Pl=0 Zn=12 Yn=Y16 SR=R0 WR=R50\n"
                      "ORG M0\nLD M1925\nFUN 86 Yn=Y30 Sn=20 Zn=5 Sv=R100 Os=R120 PR=R140 IR=R160 DR=R180 "
                      "OR=R200 WR=R220 ERR=M2\nEND\n");
  c.set("M0", 1);
  c.run_to(2100000);
  EXPECT_EQ(c.r("M2"), 1);  // Sn + Zn > 24
  EXPECT_EQ(c.r("R140"), 0);
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
