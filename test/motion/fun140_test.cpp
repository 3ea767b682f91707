// FUN140/141 in a running PLC: the manual's §11 examples in virtual time, status
// relays and registers, EN/PAU/ABT, M1991.
#include <cmath>

#include "motion_fixture.h"
#include "plc_cell/motion/profile.h"

namespace plc_cell {
namespace motion {
namespace {

constexpr double kA = 460000.0 / 0.1;  // P4 / P8 with P8 = 100 ms
constexpr double kF0 = 141;

// Closed-form duration of a DRV from standstill (trapezoid or triangle).
double drv_time(double n, double fv) {
  const double d = (fv * fv - kF0 * kF0) / (2 * kA);
  if (2 * d <= n) return 2 * (fv - kF0) / kA + (n - 2 * d) / fv;
  const double vp = std::sqrt(kF0 * kF0 + n * kA);
  return 2 * (vp - kF0) / kA;
}

TEST(Fun140, SingleMoveEmitsExactlyTheStrokeAndSetsTheStatus) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD 50000\nDRV ADR,+,100000,Ps\nGOTO NEXT\nMEND\n");
  c.run(2000);
  EXPECT_EQ(c.get("M1992"), 1u);  // ready
  c.put("M1", 1);
  c.run(1000);
  EXPECT_EQ(c.get("M10"), 1u);  // ACT
  EXPECT_EQ(c.get("M1992"), 0u);
  EXPECT_EQ(c.get("R100"), 1u);  // WR+0: step 1
  EXPECT_EQ(c.get("R101") & 0xFF, 1u);  // total steps
  EXPECT_NE(c.get("R101") & (1u << 12), 0u);
  EXPECT_GT(c.get32("DR4080"), 0);
  ASSERT_TRUE(c.run_until([&] { return c.get("M1996") == 1; }, 5000000));
  ASSERT_EQ(c.done.size(), 1u);
  const double t = 2e-3 + drv_time(100000, 50000);  // started at the 2 ms scan
  EXPECT_NEAR(c.done[0].t_ns * 1e-9, t, 1e-9);
  EXPECT_EQ(c.get32("DR4088"), 100000);
  EXPECT_EQ(c.get32("DR4072"), 0);
  EXPECT_EQ(c.get32("DR4080"), 0);
  EXPECT_EQ(c.get("R4064"), 1u);
  EXPECT_EQ(c.get("M10"), 0u);
  EXPECT_EQ(c.get("M12"), 1u);  // DN
  EXPECT_EQ(c.get("M1992"), 1u);
  EXPECT_EQ(c.get("R4060"), 0u);
  // The user clears WR+1: DN goes off.
  c.put("R101", 0);
  c.run(1000);
  EXPECT_EQ(c.get("M12"), 0u);
}

TEST(Fun140, ManualExampleB_DrvcChainReaches85000WithoutStopping) {
  MotionCell c;
  c.params(fast_params());
  c.table(R"(001 SPD 10000
    DRVC ADR,+,20000,Ut
    GOTO NEXT
002 SPD 50000
    DRVC ADR,+,60000,Ut
    GOTO NEXT
003 SPD 3000
    DRV ADR,+,5000,Ut
    WAIT X0
    GOTO 1
MEND
)");
  c.put("M1", 1);
  std::vector<int64_t> pos;
  std::vector<double> speed;
  c.unit->on_step_done([&](int, int, uint64_t t) {
    pos.push_back(c.unit->axis(0).position(t));
    speed.push_back(c.unit->axis(0).profile().end_speed());  // the section's last speed
  });
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 3; }, 10000000));
  EXPECT_EQ(c.done[0].step, 1);
  EXPECT_EQ(c.done[1].step, 2);
  EXPECT_EQ(c.done[2].step, 3);
  ASSERT_EQ(pos.size(), 3u);
  EXPECT_EQ(pos[0], 20000);
  EXPECT_EQ(pos[1], 80000);
  EXPECT_EQ(pos[2], 85000);
  EXPECT_NEAR(speed[0], 10000, 1e-6);  // no stop between the sections
  EXPECT_NEAR(speed[1], 50000, 1e-6);
  // Closed-form section times.
  const double d1 = (10000.0 * 10000 - kF0 * kF0) / (2 * kA);
  const double t1 = (10000 - kF0) / kA + (20000 - d1) / 10000;
  const double d2 = (50000.0 * 50000 - 10000.0 * 10000) / (2 * kA);
  const double t2 = (50000 - 10000) / kA + (60000 - d2) / 50000;
  const double d3a = (50000.0 * 50000 - 3000.0 * 3000) / (2 * kA), d3b = (3000.0 * 3000 - kF0 * kF0) / (2 * kA);
  const double t3 = (50000 - 3000) / kA + (5000 - d3a - d3b) / 3000 + (3000 - kF0) / kA;
  EXPECT_NEAR((c.done[0].t_ns - c.done.front().t_ns) * 1e-9, 0, 0);
  EXPECT_NEAR(c.done[0].t_ns * 1e-9, t1, 1e-8);
  EXPECT_NEAR((c.done[1].t_ns - c.done[0].t_ns) * 1e-9, t2, 1e-8);
  EXPECT_NEAR((c.done[2].t_ns - c.done[1].t_ns) * 1e-9, t3, 1e-8);
  c.run(100000);
  EXPECT_EQ(c.get32("DR4088"), 85000);
  EXPECT_NE(c.get("R101") & (1u << 9), 0u);  // waiting for X0
  EXPECT_EQ(c.done.size(), 3u);
  c.plc.set_input(0, true);
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 4; }, 10000000));
  EXPECT_EQ(c.done[3].step, 1);  // GOTO 1
  EXPECT_EQ(pos[3], 105000);
}

TEST(Fun140, ManualExampleA_ExtLeavesTheRestInDR4072AndStep4SendsIt) {
  MotionCell c;
  c.params(fast_params());
  c.table(kExample1);
  c.put("DR1000", 8000);
  c.put("DD100", 3000);
  c.put("R500", 50);  // 0.5 s
  c.put("DR1002", 4000);
  c.put("DD102", 6000);
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 2; }, 10000000));
  EXPECT_EQ(c.get32("DR4088"), 13000);
  // Step 1 ends, waits exactly 1 s, step 2 starts then.
  const double t1 = drv_time(10000, 5000);
  EXPECT_NEAR(c.done[0].t_ns * 1e-9, t1, 1e-8);
  EXPECT_NEAR((c.done[1].t_ns - c.done[0].t_ns) * 1e-9, 1.0 + drv_time(3000, 8000), 1e-8);
  // Step 3 starts 0.5 s later; X0 (slow-down point) 0.8 s into it.
  const uint64_t x0_at_us = (c.done[1].t_ns + 500000000 + 800000000) / 1000;
  c.run(x0_at_us - c.now_us);
  c.plc.set_input(0, true);
  c.run(1000);
  ASSERT_EQ(c.done.size(), 3u);
  EXPECT_EQ(c.done[2].step, 3);
  const int32_t moved = 13000 - c.unit->axis(0).position(c.done[2].t_ns);
  EXPECT_GT(moved, 0);
  EXPECT_LT(moved, 6000);
  c.plc.set_input(0, false);
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 4; }, 10000000));
  EXPECT_EQ(c.done[3].step, 4);
  EXPECT_EQ(c.get32("DR4088"), 13000 - 6000);  // steps 3 + 4 = exactly DD102 back
  c.run(50000);
  EXPECT_EQ(c.done.size(), 4u);  // waits for X1
  c.plc.set_input(1, true);
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 5; }, 10000000));
  EXPECT_EQ(c.done[4].step, 1);
  EXPECT_EQ(c.get32("DR4088"), 17000);
}

TEST(Fun140, EnOffStopsAtOnceAndEnOnRunsTheNextStep) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD 1000\nDRV ADR,+,5000,Ps\nGOTO NEXT\nSPD 1000\nDRV ADR,+,100,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(1001000);
  const int32_t at = c.get32("DR4088");
  c.put("M1", 0);
  c.run(1000);  // the scan sees EN = 0 at 1.001 s
  const int32_t stopped = c.get32("DR4088");
  EXPECT_EQ(c.get32("DR4080"), 0);
  EXPECT_GE(stopped, at);
  EXPECT_LE(stopped, at + 2);  // at most the pulses of one 1 ms scan at 1 kHz
  c.run(100000);
  EXPECT_EQ(c.get32("DR4088"), stopped);
  EXPECT_EQ(c.get("R100"), 1u);  // stopped in step 1
  EXPECT_EQ(c.get("M1992"), 1u);
  c.put("M1", 1);  // the next step: 2
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 1; }, 1000000));
  EXPECT_EQ(c.done[0].step, 2);
  EXPECT_EQ(c.get32("DR4088"), stopped + 100);
}

TEST(Fun140, AbortWithM1991DeceleratesAndRestartsAtTheFirstStep) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD 100000\nDRV ADR,+,1000000,Ps\nGOTO NEXT\nSPD 1000\nDRV ADR,+,100,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1991", 1);
  c.put("M1", 1);
  c.run(200000);  // cruising at 100 kHz
  EXPECT_EQ(c.get32("DR4080"), 100000);
  c.put("M3", 1);
  c.run(1000);  // the scan that sees ABT: deceleration starts at its instant
  const int32_t at = c.get32("DR4088");
  c.run(1000);
  EXPECT_GT(c.get32("DR4080"), 0);  // still decelerating
  EXPECT_LT(c.get32("DR4080"), 100000);
  c.run(100000);
  EXPECT_EQ(c.get32("DR4080"), 0);
  // Pulses of a deceleration from 100 kHz to 141 Hz at 4.6 MHz/s.
  const double d = (1e10 - kF0 * kF0) / (2 * kA);
  const int32_t end = c.get32("DR4088");
  EXPECT_NEAR(end - at, std::ceil(d), 1);
  EXPECT_EQ(c.get("R100"), 0u);
  EXPECT_TRUE(c.done.empty());
  c.put("M3", 0);
  c.put("M1", 0);
  c.run(1000);
  c.put("M1", 1);
  c.run(1000);
  EXPECT_EQ(c.get("R100"), 1u);  // from the first step again
}

TEST(Fun140, PauseAndResumeFinishTheStroke) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD 10000\nDRV ADR,+,20000,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(500000);
  c.put("M2", 1);
  c.run(1000);
  const int32_t p = c.get32("DR4088");
  c.run(300000);
  EXPECT_EQ(c.get32("DR4088"), p);
  EXPECT_NE(c.get("R101") & (1u << 8), 0u);  // paused
  EXPECT_EQ(c.get32("DR4072"), 20000 - p);
  c.put("M2", 0);
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 1; }, 5000000));
  EXPECT_EQ(c.get32("DR4088"), 20000);
}

TEST(Fun140, EndlessRotationRunsUntilEnOff) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD 20000\nDRV ADR,-,0,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(1001000);
  EXPECT_NE(c.get("R101") & (1u << 10), 0u);
  EXPECT_EQ(c.get32("DR4080"), 20000);
  // 1 s from the start: ramp + cruise, backwards.
  const double ta = (20000 - kF0) / kA, sa = (20000.0 * 20000 - kF0 * kF0) / (2 * kA);
  EXPECT_NEAR(-c.get32("DR4088"), std::floor(sa + (1.0 - ta) * 20000), 1);
  c.put("M1", 0);
  c.run(1000);
  EXPECT_EQ(c.get32("DR4080"), 0);
}

TEST(Fun140, SpeedZeroWaitsForTheRegister) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD D10\nDRV ADR,+,100,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(100000);
  EXPECT_EQ(c.get32("DR4088"), 0);
  EXPECT_EQ(c.get("M1992"), 0u);  // the program holds the axis
  c.put("DD10", 1000);
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 1; }, 1000000));
  EXPECT_EQ(c.get32("DR4088"), 100);
}

TEST(Fun140, AbsoluteMovesAndGotoRegister) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD 5000\nDRV ABS, ,300,Ps\nGOTO R200\nSPD 5000\nDRV ABS, ,-50,Ps\nGOTO NEXT\nSPD 5000\nDRV ABS, ,0,Ps\nGOTO NEXT\nMEND\n");
  c.put("R200", 3);
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.get("M1996") == 1; }, 5000000));
  ASSERT_EQ(c.done.size(), 2u);
  EXPECT_EQ(c.done[0].step, 1);
  EXPECT_EQ(c.done[1].step, 3);  // GOTO R200 = 3
  EXPECT_EQ(c.get32("DR4088"), 0);
}

TEST(Fun140, BacklashAndCompensationAddPulsesNotPosition) {
  MotionCell c;
  AxisParams p = fast_params();
  p.p7_backlash = 30;
  p.p11_bwd_comp = 5;
  p.p10_fwd_comp = 7;
  c.params(p);
  c.table("SPD 5000\nDRV ADR,+,1000,Ps\nGOTO NEXT\nSPD 5000\nDRV ADR,-,1000,Ps\nGOTO NEXT\nMEND\n");
  int64_t fwd = 0, back = 0;
  c.unit->on_step_done([&](int, int step, uint64_t t) {
    (step == 1 ? fwd : back) = c.unit->axis(0).pulse_count(t);
  });
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.get("M1996") == 1; }, 5000000));
  EXPECT_EQ(fwd, 1007);
  EXPECT_EQ(back, 1007 - 1035);
  EXPECT_EQ(c.get32("DR4088"), 0);
  EXPECT_NEAR(c.done[1].t_ns * 1e-9 - c.done[0].t_ns * 1e-9, drv_time(1035, 5000), 1e-8);
}

TEST(Fun140, BadParametersGiveTheirCodeAndNothingMoves) {
  MotionCell c;
  AxisParams p = fast_params();
  p.p8_acc_ms = 30001;
  c.params(p);
  c.table("SPD 5000\nDRV ADR,+,1000,Ps\nGOTO NEXT\nMEND\n");
  c.run(1000);
  EXPECT_EQ(c.get("R4060"), 9u);
  EXPECT_EQ(c.get("M13"), 1u);
}

TEST(Fun140, BadTableInRegistersIsAnErrorAndNothingMoves) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD 5000\nDRV ADR,+,1000,Ps\nGOTO NEXT\nMEND\n");
  c.put("R1", 0);  // magic word gone
  c.put("M1", 1);
  c.run(100000);
  EXPECT_EQ(c.get("M11"), 1u);
  EXPECT_EQ(c.get("R4060"), 34u);
  EXPECT_EQ(c.get32("DR4088"), 0);
  EXPECT_EQ(c.get("M1992"), 1u);
}

TEST(Fun140, RuntimeStrokeOutOfRangeIsCode33) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD 5000\nDRV ADR,+,D0,Ps\nGOTO NEXT\nMEND\n");
  c.put("DD0", 100000000);
  c.put("M1", 1);
  c.run(10000);
  EXPECT_EQ(c.get("R4060"), 33u);
  EXPECT_EQ(c.get("M11"), 1u);
  EXPECT_EQ(c.get32("DR4088"), 0);
}

TEST(Fun140, LadderWritesThePositionRegister) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD 5000\nDRV ABS, ,0,Ps\nGOTO NEXT\nMEND\n");
  c.run(1000);
  c.put("DR4088", 100);  // e.g. a homing routine
  c.run(1000);
  EXPECT_EQ(c.get32("DR4088"), 100);
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 1; }, 1000000));
  EXPECT_EQ(c.get32("DR4088"), 0);
}

}  // namespace
// Found by the whole-cell fuzzer: steps with nothing to move (ABS to where the axis
// stands) that GOTO each other never let time pass. Each such step completed and started
// the next inside the same call, so the stack overflowed. The loop is refused as the
// text form's GOTO errors are (code 34), with ERR on, and the axis stays where it was.
TEST(Fun140, GotoLoopOfEmptyStepsIsCode34NotAStackOverflow) {
  MotionCell c;
  c.params(fast_params());
  c.table("001 SPD 5000\n    DRV ABS,,0,Ps\n    GOTO 2\n002 SPD 5000\n    DRV ABS,,0,Ps\n    GOTO 1\nMEND\n");
  c.put("M1", 1);
  c.run(10000);
  EXPECT_EQ(c.get("R4060"), 34u);
  EXPECT_EQ(c.get("M11"), 1u);
  EXPECT_EQ(c.get32("DR4088"), 0);
}

// A step with nothing to move that is not part of a loop still completes at once.
TEST(Fun140, EmptyStepFollowedByAMoveCompletes) {
  MotionCell c;
  c.params(fast_params());
  c.table("001 SPD 5000\n    DRV ABS,,0,Ps\n    GOTO NEXT\n002 SPD 5000\n    DRV ADR,+,100,Ps\n    GOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(100000);
  EXPECT_EQ(c.get("R4060"), 0u);
  EXPECT_EQ(c.get("M11"), 0u);
  EXPECT_EQ(c.get32("DR4088"), 100);
}

}  // namespace motion
}  // namespace plc_cell
