// FUN142 PSOFF, FUN143 PSCNV, the ACT transfer condition and two FUN140s sharing an axis.
#include <cmath>

#include "motion_fixture.h"

namespace plc_cell {
namespace motion {
namespace {

constexpr const char* kWithOff = R"(ORG M1925
MPARA Ps=0 SR=R2000
ORG M1
LD M2
LD M3
HSPSO Ps=0 SR=R0 WR=R100 ACT=M10 ERR=M11 DN=M12
ORG M20
PSOFF.P N=0
ORG M1925
PSCNV Ps=0 D=R300
END
)";

TEST(Fun142, StopsTheOutputAtOnceWithM1991Off) {
  MotionCell c(kWithOff);
  c.params(fast_params());
  c.table("SPD 10000\nDRV ADR,+,100000,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(300000);
  c.put("M20", 1);
  c.run(1000);
  const int32_t p = c.get32("DR4088");
  EXPECT_EQ(c.get32("DR4080"), 0);
  c.run(100000);
  EXPECT_EQ(c.get32("DR4088"), p);
  EXPECT_EQ(c.get32("DR4072"), 100000 - p);  // what is left unsent
  EXPECT_EQ(c.get("M1992"), 1u);
}

TEST(Fun142, DeceleratesWithM1991On) {
  MotionCell c(kWithOff);
  c.params(fast_params());
  c.table("SPD 10000\nDRV ADR,+,100000,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1991", 1);
  c.put("M1", 1);
  c.run(300000);
  c.put("M20", 1);
  c.run(1000);
  const int32_t p = c.get32("DR4088");
  c.run(100000);
  const double d = (1e8 - 141.0 * 141) / (2 * 4.6e6);  // 10 kHz -> 141 Hz
  EXPECT_EQ(c.get32("DR4088") - p, static_cast<int32_t>(std::ceil(d)));
}

TEST(Fun143, ConvertsThePositionToUt) {
  MotionCell c(kWithOff);
  AxisParams p = fast_params();
  p.p0_unit = 2;        // compound: stroke in mm
  p.p2_per_rev = 5000;  // 5 mm per revolution of 2000 pulses
  p.p3_res = 2;         // Ut = 0.01 mm
  c.params(p);
  c.table("SPD 10000\nDRV ADR,+,1234,Ut\nGOTO NEXT\nMEND\n");  // 12.34 mm = 4936 pulses
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 1; }, 5000000));
  c.run(1000);
  EXPECT_EQ(c.get32("DR4088"), 4936);
  EXPECT_EQ(c.get32("DR300"), 1234);
}

TEST(Fun140Act, GoesOnAtTheTimeEvenIfPulsesRemain) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD 1000\nDRV ADR,+,100000,Ps\nACT Time,50\nGOTO NEXT\nSPD 1000\nDRV ADR,+,10,Ps\nACT Time,100\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 2; }, 5000000));
  // Step 1 is cut 0.5 s after its start (at the 0 ms scan); step 2 ends its 10 pulses
  // early and waits for its 1 s.
  EXPECT_EQ(c.done[0].t_ns, 500000000u);
  const double d = (1e6 - 141.0 * 141) / (2 * 4.6e6);
  const double t2 = 2 * (1000 - 141) / 4.6e6 + (10 - 2 * d) / 1000;
  EXPECT_NEAR(c.done[1].t_ns * 1e-9, 0.5 + t2, 1e-8);
  // Step 1: what 0.5 s sent (499.92 pulses: the 500th is past its half, its edge is
  // out, so the cut completes it: docs/motion.md "Pulse pins"), then step 2's 10.
  const double ta = (1000 - 141) / 4.6e6;
  EXPECT_EQ(c.get32("DR4088"), static_cast<int32_t>(std::floor(d + (0.5 - ta) * 1000 + 0.5)) + 10);
  ASSERT_TRUE(c.run_until([&] { return c.get("M1996") == 1; }, 5000000));
  // The program ends 1 s after step 2 started (the 1.5 s scan sees it), not when its pulses ended.
  EXPECT_EQ(c.now_us, 1501000u);
}

constexpr const char* kTwoOnOneAxis = R"(ORG M1925
MPARA Ps=0 SR=R2000
ORG M1
LD M2
LD M3
HSPSO Ps=0 SR=R0 WR=R100 ACT=M10 ERR=M11 DN=M12
ORG M4
LD M5
LD M6
HSPSO Ps=0 SR=R50 WR=R110 ACT=M14 ERR=M15 DN=M16
END
)";

TEST(Fun140Sharing, TheSecondStartsWhenTheFirstReleasesTheAxis) {
  MotionCell c(kTwoOnOneAxis);
  c.params(fast_params());
  c.table("SPD 1000\nDRV ADR,+,500,Ps\nGOTO NEXT\nMEND\n", 0);
  c.table("SPD 1000\nDRV ADR,-,200,Ps\nGOTO NEXT\nMEND\n", 50);
  c.put("M1", 1);
  c.run(1000);
  c.put("M4", 1);  // EN of the second while the first holds the axis
  c.run(100000);
  EXPECT_EQ(c.get("M14"), 0u);
  EXPECT_EQ(c.get("M10"), 1u);
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 2; }, 5000000));
  EXPECT_EQ(c.get32("DR4088"), 300);
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell
