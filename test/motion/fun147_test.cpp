// FUN147 MHSP0 in a running PLC: the manual's example C in virtual time, the
// simultaneous start and end of the axes, LINE chains, resource management with
// FUN140, PAU/EN/ABT, errors with nothing moving.
#include <cmath>

#include "motion_fixture.h"

namespace plc_cell {
namespace motion {
namespace {

struct GroupDone {
  int gp, step;
  uint64_t t_ns;
  int64_t pos[4];
  double v_end[4];  // each axis's speed at the end of the step's profile
};

// A move ending at speed 0 ends on a double root of s(t) = N: the floating-point
// error of the instant is about sqrt(1e-16 N / a) s, far below one pulse period.
constexpr double kEndTol = 1e-7;

// A cell running kGroup0Program (or a variant) that logs every group step end
// with the four positions at that instant.
struct GroupCell : MotionCell {
  explicit GroupCell(const std::string& il = kGroup0Program) : MotionCell(il) {
    unit->interpolation().on_step_done([this](int gp, int step, uint64_t t) {
      GroupDone d{gp, step, t, {}};
      for (int n = 0; n < 4; ++n) {
        d.pos[n] = unit->axis(n).position(t);
        d.v_end[n] = unit->axis(n).profile().end_speed();
      }
      gdone.push_back(d);
    });
    params(AxisParams{});  // the manual's defaults: P13 = 500 ms
    run(2000);             // MPARA has run; the next scan is at 2 ms
  }
  std::vector<GroupDone> gdone;
};

// Closed form of one LIN step from standstill to standstill: vector speed v (Hz),
// path length len (pulses), P13 = t13 s: a = v / t13; triangle if v * t13 > len.
double lin_time(double len, double v, double t13 = 0.5) {
  const double a = v / t13;
  if (v * t13 >= len) return 2 * std::sqrt(len / a);
  return t13 + len / v;
}

void expect_positions(const GroupDone& d, int64_t p0, int64_t p1, int64_t p2, int64_t p3) {
  EXPECT_EQ(d.pos[0], p0) << "step " << d.step;
  EXPECT_EQ(d.pos[1], p1) << "step " << d.step;
  EXPECT_EQ(d.pos[2], p2) << "step " << d.step;
  EXPECT_EQ(d.pos[3], p3) << "step " << d.step;
}

TEST(Fun147, ManualExampleC_EveryStepEndsTogetherAtTheClosedFormInstant) {
  GroupCell c;
  c.lin_table(kExampleC);
  c.put("DR1000", 1000);  // step 2: vector 1 kHz, Ps0 = 1000, Ps1 = 500 (the manual's figure)
  c.put("DD100", 1000);
  c.put("DD200", 500);
  c.put("R500", 50);      // wait 0.5 s
  c.put("DR1002", 2000);  // step 3: Ps2 = -300, Ps3 = +400 (|s| = 500)
  c.put("DR300", static_cast<uint32_t>(-300));
  c.put("DR400", 400);
  c.put("M1", 1);
  c.run(1000);  // started at the 2 ms scan
  const double t0 = 2e-3;
  // Every axis runs the lead profile scaled: all four end on the same ns.
  const uint64_t end = c.unit->axis(0).end_ns();
  for (int n = 1; n < 4; ++n) EXPECT_EQ(c.unit->axis(n).end_ns(), end) << n;
  for (int n = 0; n < 4; ++n) EXPECT_EQ(c.get("M" + std::to_string(1992 + n)), 0u) << "axis " << n << " held";
  EXPECT_EQ(c.get("M10"), 1u);  // ACT
  EXPECT_EQ(c.get("R100"), 1u);
  EXPECT_EQ(c.get("R101") & 0xFF, 3u);

  ASSERT_TRUE(c.run_until([&] { return c.gdone.size() == 3; }, 10000000));
  // Step 1: |s| = sqrt(500^2 + 400^2 + 300^2 + 200^2) = 734.85 at 5 kHz, a = 10 kHz/s: triangle.
  const double t1 = t0 + lin_time(std::sqrt(540000.0), 5000);
  EXPECT_NEAR(c.gdone[0].t_ns * 1e-9, t1, kEndTol);
  expect_positions(c.gdone[0], 500, 400, 300, 200);
  // Step 2 after WAIT 1 s: |s| = 1118.03 at 1 kHz, a = 2 kHz/s: 0.5 s ramps + cruise.
  const double t2 = t1 + 1.0 + lin_time(std::sqrt(1250000.0), 1000);
  EXPECT_NEAR(c.gdone[1].t_ns * 1e-9, t2, kEndTol);
  expect_positions(c.gdone[1], 1500, 900, 300, 200);
  // Step 3 after WAIT 0.5 s: |s| = 500 at 2 kHz: triangle.
  const double t3 = t2 + 0.5 + lin_time(500, 2000);
  EXPECT_NEAR(c.gdone[2].t_ns * 1e-9, t3, kEndTol);
  expect_positions(c.gdone[2], 1500, 900, 0, 600);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(c.gdone[k].step, k + 1);
  // Pulse counts: every pulse of a step in its own direction (P9 is not used by FUN147).
  const int64_t counts[4] = {1500, 900, 0, 600};  // Ps2: 300 pulses up, then 300 down
  for (int n = 0; n < 4; ++n) EXPECT_EQ(c.unit->axis(n).pulse_count(c.gdone[2].t_ns), counts[n]) << n;
  EXPECT_EQ(c.get("D4062"), 3u);
  EXPECT_EQ(c.get("D4060"), 0u);
  EXPECT_EQ(c.get("M1934"), 0u);  // GOTO 1: never the last step
  c.run(1000);
  EXPECT_NE(c.get("R101") & (1u << 9), 0u);  // waiting for X0
  EXPECT_EQ(c.get("M10"), 0u);
  EXPECT_EQ(c.get("M12"), 1u);  // DN
  // X0 -> step 1 again: +500 +400 +300 +200 from there.
  c.plc.set_input(0, true);
  ASSERT_TRUE(c.run_until([&] { return c.gdone.size() == 4; }, 5000000));
  EXPECT_EQ(c.gdone[3].step, 1);
  expect_positions(c.gdone[3], 2000, 1300, 300, 800);
  c.run(1000);
  EXPECT_EQ(c.get32("DR4088"), 2000);
  EXPECT_EQ(c.get32("DR4094"), 800);
}

TEST(Fun147, FigureCase1000And500PsPulsesStayProportionalAndEndTogether) {
  GroupCell c;
  c.lin_table("SPD 1000\nLIN ADR,1000,500, , ,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(1000);
  const Axis& x = c.unit->axis(0);
  const Axis& y = c.unit->axis(1);
  // Ps1's pulse k falls with Ps0's pulse 2k (the path stays on the line), the last on the same ns.
  for (int k = 1; k <= 500; ++k) {
    const int64_t dt = int64_t(y.when_at(k)) - int64_t(x.when_at(2 * k));
    ASSERT_LE(std::llabs(dt), 2) << "pulse " << k;
  }
  EXPECT_EQ(x.end_ns(), y.end_ns());
  EXPECT_EQ(x.emitted(x.end_ns()), 1000);  // exactly the strokes
  EXPECT_EQ(y.emitted(y.end_ns()), 500);
  // Cruise at 1 kHz along the line: Ps0 at 1000 x 1000/1118.03 = 894.4 Hz, Ps1 at 447.2 Hz.
  c.run(800000);  // 0.803 s: the ramps are 0.5 s
  EXPECT_EQ(c.get32("DR4080"), 894);
  EXPECT_EQ(c.get32("DR4082"), 447);
  EXPECT_EQ(c.get32("DR4068"), 1000);  // vector speed
  EXPECT_EQ(c.get("M1994"), 1u);       // Ps2, Ps3 not named by the table: not held
  EXPECT_EQ(c.get("M1995"), 1u);
  ASSERT_TRUE(c.run_until([&] { return c.get("M1934") == 1; }, 5000000));
  EXPECT_NEAR(c.gdone[0].t_ns * 1e-9, 2e-3 + lin_time(std::sqrt(1250000.0), 1000), kEndTol);
  EXPECT_EQ(c.get32("DR4088"), 1000);
  EXPECT_EQ(c.get32("DR4090"), 500);
  EXPECT_EQ(c.get32("DR4068"), 0);
  EXPECT_EQ(c.get("D4062"), 1u);
  EXPECT_EQ(c.get("M1992"), 1u);  // released
  EXPECT_EQ(c.get("M10"), 0u);
}

TEST(Fun147, LineChainsWithoutStoppingAndAbsReturns) {
  GroupCell c;
  // LINE: +1000 on Ps0 ends at 1 kHz; the LIN +1000 on Ps1 starts from it (a corner).
  c.lin_table("SPD 1000\nLINE ADR,1000, , , \nGOTO NEXT\nSPD 1000\nLIN ADR, ,1000, , \nGOTO NEXT\n"
              "SPD 4000\nLIN ABS,0,0, , \nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.gdone.size() == 3; }, 10000000));
  // a = 1000 / 0.5 s. Step 1: 0.5 s ramp (250 pulses) + 750 at 1 kHz, no deceleration.
  EXPECT_NEAR(c.gdone[0].t_ns * 1e-9, 2e-3 + 1.25, kEndTol);
  EXPECT_NEAR(c.gdone[0].v_end[0], 1000, 1e-6);  // LINE: no deceleration at the step's end
  // Step 2 from 1 kHz: 750 at 1 kHz, then the 0.5 s ramp down (250).
  EXPECT_NEAR(c.gdone[1].t_ns * 1e-9, 2e-3 + 2.5, kEndTol);
  expect_positions(c.gdone[1], 1000, 1000, 0, 0);
  // ABS 0,0: back along the diagonal |s| = 1414.2 at 4 kHz (triangle, a = 8 kHz/s).
  EXPECT_NEAR(c.gdone[2].t_ns * 1e-9, 2e-3 + 2.5 + lin_time(std::sqrt(2e6), 4000), kEndTol);
  expect_positions(c.gdone[2], 0, 0, 0, 0);
}

TEST(Fun147, P13OfTheLongestAxisSetsTheRamp) {
  std::string il = kGroup0Program;
  il.replace(il.find("Ps=1 SR=R2000"), 13, "Ps=1 SR=R2100");
  GroupCell c(il);
  AxisParams p;
  p.p13_interp_ms = 100;
  c.params(p, 2100);  // Ps1: P13 = 100 ms; Ps0 keeps 500 ms
  c.run(1000);
  c.lin_table("SPD 1000\nLIN ADR,100,2000, , \nGOTO NEXT\nSPD 1000\nLIN ADR,2000,100, , \nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.gdone.size() == 2; }, 10000000));
  const double len = std::sqrt(100.0 * 100 + 2000.0 * 2000);
  const double t_first = 3e-3 + lin_time(len, 1000, 0.1);  // Ps1 is the longest: 100 ms
  EXPECT_NEAR(c.gdone[0].t_ns * 1e-9, t_first, kEndTol);
  EXPECT_NEAR(c.gdone[1].t_ns * 1e-9, t_first + lin_time(len, 1000, 0.5), kEndTol);  // Ps0: 500 ms
}

TEST(Fun147, WaitsForAnAxisHeldByFun140AndViceVersa) {
  std::string il = kGroup0Program;
  il.replace(il.find("END"), 3, "ORG M4\nLD M5\nLD M6\nHSPSO Ps=0 SR=R400 WR=R150 ACT=M20 ERR=M21 DN=M22\nEND");
  GroupCell c(il);
  c.table("SPD 10000\nDRV ADR,+,5000,Ps\nGOTO NEXT\nMEND\n", 400);
  c.lin_table("SPD 1000\nLIN ADR,100,100, , \nGOTO NEXT\nMEND\n");
  c.put("M4", 1);  // FUN140 takes Ps0
  c.run(1000);
  c.put("M1", 1);  // FUN147 must wait for Ps0
  c.run(5000);
  EXPECT_EQ(c.get("R100"), 0u);
  EXPECT_EQ(c.get("M1993"), 1u);  // Ps1 not taken while waiting
  EXPECT_EQ(c.get32("DR4090"), 0);
  ASSERT_TRUE(c.run_until([&] { return c.get("M1996") == 1; }, 5000000));  // FUN140 done: Ps0 free
  ASSERT_TRUE(c.run_until([&] { return c.get("M1934") == 1; }, 5000000));
  EXPECT_EQ(c.get32("DR4088"), 5100);
  EXPECT_EQ(c.get32("DR4090"), 100);
  // Now the group holds Ps0 and the FUN140 (EN toggled) waits for it.
  c.put("M1", 0);
  c.put("M4", 0);
  c.run(1000);
  c.lin_table("SPD 1000\nLIN ADR,1000,1000, , \nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(1000);
  c.put("M4", 1);
  c.run(100000);
  EXPECT_EQ(c.get("M20"), 0u);  // FUN140 not sending
  EXPECT_EQ(c.get("M1992"), 0u);
  ASSERT_TRUE(c.run_until([&] { return c.get("M1934") == 1; }, 5000000));
  ASSERT_TRUE(c.run_until([&] { return c.get("M1996") == 1; }, 5000000));  // then FUN140 runs
  EXPECT_EQ(c.get32("DR4088"), 5100 + 1000 + 5000);
}

TEST(Fun147, PauseResumeAndEnOffKeepExactCounts) {
  GroupCell c;
  c.lin_table("SPD 2000\nLIN ADR,3000,-1500, , \nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(600000);
  c.put("M2", 1);  // PAU (M1991 off: at once)
  c.run(1000);
  const int32_t x = c.get32("DR4088"), y = c.get32("DR4090");
  EXPECT_GT(x, 0);
  EXPECT_LT(x, 3000);
  EXPECT_NEAR(double(y), -x / 2.0, 1.0);  // on the line within one pulse
  EXPECT_NE(c.get("R101") & (1u << 8), 0u);
  EXPECT_EQ(c.get32("DR4072"), 3000 - x);  // what is left per axis
  c.run(100000);
  EXPECT_EQ(c.get32("DR4088"), x);  // nothing moves while paused
  c.put("M2", 0);
  ASSERT_TRUE(c.run_until([&] { return c.get("M1934") == 1; }, 10000000));
  EXPECT_EQ(c.get32("DR4088"), 3000);
  EXPECT_EQ(c.get32("DR4090"), -1500);
  // EN off mid-move with M1991 on: a decelerated stop, then nothing more.
  c.put("M1", 0);
  c.run(1000);
  c.put("M1", 1);
  c.put("M1991", 1);
  c.run(700000);
  EXPECT_EQ(c.get32("DR4080"), 1789);  // cruise: 2000 x 3000 / 3354.1
  c.put("M1", 0);
  c.run(50000);
  // Slowing at 2000 / 0.5 s x 0.894 = 3578 Hz/s: about 1789 - 179 after 50 ms.
  EXPECT_NEAR(c.get32("DR4080"), 1789 - 179, 5);
  c.run(2000000);
  EXPECT_EQ(c.get32("DR4080"), 0);
  EXPECT_EQ(c.get("M1992"), 1u);
  EXPECT_LT(c.get32("DR4088"), 6000);  // stopped short of the second target
}

// FUN142 PSOFF on one axis of a group stops the whole group (its axes move as one):
// at once with M1991 off, the rest of each axis in DR4072; nothing moves afterwards.
TEST(Fun147, PsoffOnOneAxisStopsTheGroup) {
  std::string il = kGroup0Program;
  il.replace(il.find("END"), 3, "ORG M5\nPSOFF.P N=1\nEND");
  GroupCell c(il);
  c.lin_table("SPD 2000\nLIN ADR,3000,-1500, , \nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(600000);
  c.put("M5", 1);  // PSOFF Ps1
  c.run(1000);
  const int32_t x = c.get32("DR4088"), y = c.get32("DR4090");
  EXPECT_GT(x, 0);
  EXPECT_LT(x, 3000);
  EXPECT_NEAR(double(y), -x / 2.0, 1.0);  // both stopped on the line
  EXPECT_EQ(c.get32("DR4072"), 3000 - x);
  EXPECT_EQ(c.get32("DR4080") + c.get32("DR4082"), 0);
  EXPECT_EQ(c.get("M1992") + c.get("M1993"), 2u);  // both axes free again
  c.run(500000);
  EXPECT_EQ(c.get32("DR4088"), x);
  EXPECT_EQ(c.get32("DR4090"), y);
}

TEST(Fun147, ErrorsStopWithTheirCodeAndNothingMoves) {
  {  // Gp1 is Ps2 & Ps3: a table naming Ps0 is illegal (code 60 in D4061)
    std::string il = kGroup0Program;
    il.replace(il.find("Gp=0"), 4, "Gp=1");
    GroupCell c(il);
    c.lin_table("SPD 1000\nLIN ADR,100, ,100, \nGOTO NEXT\nMEND\n");
    c.put("M1", 1);
    c.run(10000);
    EXPECT_EQ(c.get("D4061"), 60u);
    EXPECT_EQ(c.get("M11"), 1u);
    EXPECT_EQ(c.get32("DR4088"), 0);
    EXPECT_EQ(c.get32("DR4092"), 0);
    EXPECT_EQ(c.get("M1992"), 1u);
    EXPECT_EQ(c.get("D4060"), 0u);
  }
  {  // a stroke register out of range at run time: 33; a broken image: 34
    GroupCell c;
    c.lin_table("SPD 1000\nLIN ADR,D10,100, , \nGOTO NEXT\nMEND\n");
    c.put("DD10", 100000000);
    c.put("M1", 1);
    c.run(10000);
    EXPECT_EQ(c.get("D4060"), 33u);
    EXPECT_EQ(c.get("M11"), 1u);
    EXPECT_EQ(c.get32("DR4090"), 0);
    EXPECT_EQ(c.get("M1993"), 1u);
    c.put("M1", 0);
    c.put("R1", 0x140A);  // not a FUN147 table
    c.run(1000);
    c.put("M1", 1);
    c.run(10000);
    EXPECT_EQ(c.get("D4060"), 34u);
    EXPECT_EQ(c.get32("DR4088"), 0);
  }
}

TEST(Fun147, RunsOnEveryOutputModeIncludingPR) {
  // AMBIG-22: the manual lists U/D and A/B for FUN147; plc_cell does not refuse P/R
  // (the output stage is the axis's, the same for FUN140 and FUN147).
  GroupCell c;
  AxesConfig cfg;
  cfg.axes[0].used = cfg.axes[1].used = cfg.axes[2].used = true;
  cfg.axes[0].mode = OutputMode::UD;
  cfg.axes[1].mode = OutputMode::PR;
  cfg.axes[2].mode = OutputMode::AB;
  c.with([&](MotionUnit& u) {
    u.configure(cfg);
    return 0;
  });
  c.lin_table("SPD 3000\nLIN ADR,-700,300,100, ,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.get("M1934") == 1; }, 5000000));
  EXPECT_EQ(c.get("M11"), 0u);
  expect_positions(c.gdone[0], -700, 300, 100, 0);
}

TEST(Fun147, AbortRestartsFromTheFirstStep) {
  GroupCell c;
  c.lin_table("SPD 1000\nLIN ADR,100,100, , \nWAIT M7\nGOTO NEXT\nSPD 1000\nLIN ADR,100, , , \nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.gdone.size() == 1; }, 5000000));
  c.put("M3", 1);  // ABT while waiting
  c.run(1000);
  EXPECT_EQ(c.get("R100"), 0u);
  EXPECT_EQ(c.get("M1992"), 1u);
  c.put("M3", 0);
  c.put("M1", 0);
  c.run(1000);
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.gdone.size() == 2; }, 5000000));
  EXPECT_EQ(c.gdone[1].step, 1);  // from the first step again
  EXPECT_EQ(c.get32("DR4088"), 200);
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell
