// The `stepspeed:` form of an axis ramp (the TRi FMD1616's STEPSPEED, manual Ch. 10):
// the ramp in steps, the completion relay, the move lock, the direction pin and the
// configuration errors (docs/motion.md "Step-count ramps (stepspeed:)").
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>

#include "motion_fixture.h"
#include "plc_cell/core/error.h"
#include "plc_cell/motion/pulse_pins.h"
#include "plc_cell/timeline/scheduler.h"

namespace plc_cell {
namespace motion {
namespace {

// The manual's example, STEPSPEED 1,100,50: V = 100 pps reached in S = 50 steps, so
// A = V^2 / 2S = 100^2 / (2 * 50) = 100 pps^2, and the train runs from V/8 = 12.5 pps.
constexpr double kV = 100, kS = 50;
constexpr double kA = kV * kV / (2 * kS);
constexpr double kV0 = kV / 8;
static_assert(kA == 100, "the manual's worked value");

// The manual's ramp in closed form, for a move of n steps: the instant (s from the
// move's start) at which travel reaches s, and the whole duration.
struct Trapezoid {
  double n;
  double vp;  // peak: V, or lower when the two ramps meet (triangle)
  double ramp_dist() const { return (vp * vp - kV0 * kV0) / (2 * kA); }
  double ramp_time() const { return (vp - kV0) / kA; }
  double duration() const { return 2 * ramp_time() + (n - 2 * ramp_dist()) / vp; }
  double time_at(double s) const {
    const auto up = [](double x) { return (-kV0 + std::sqrt(kV0 * kV0 + 2 * kA * x)) / kA; };
    if (s <= ramp_dist()) return up(s);
    if (s <= n - ramp_dist()) return ramp_time() + (s - ramp_dist()) / vp;
    return duration() - up(n - s);
  }
  static Trapezoid of(double n) {
    const double full = 2 * (kV * kV - kV0 * kV0) / (2 * kA);  // both ramps to V
    return {n, n >= full ? kV : std::sqrt(kV0 * kV0 + kA * n)};
  }
};

constexpr uint64_t kSec = 1000000000;

const char* const kYaml = "axes:\n  pso0: {output: PR, stepspeed: {pps: 100, accel_steps: 50, done: M100}}\n";

class StepCell : public MotionCell {
 public:
  explicit StepCell(const std::string& yaml = kYaml, const std::string& il = kAxis0Program) : MotionCell(il) {
    unit->configure(parse_axes_config(YAML::Load(yaml)["axes"], "cell.yaml"));
    // FUN141 asks for a different ramp (P8 = 100 ms, P5 = 141 Hz): stepspeed replaces it.
    params(fast_params());
  }
  const Axis& ax() { return unit->axis(0); }
  // The cell's clock brought to t_ns between scans, as the scheduler does.
  void clock_to(uint64_t t_ns) {
    plc.locked([&](ScanEngine& e, Memory&) {
      timeline::Scheduler::of(e).advance(t_ns);
      return 0;
    });
  }
};

// STEPMOVE 1,500,101 after STEPSPEED 1,100,50, with the move started by FUN140 (its SPD
// is not used: the step form has one speed).
TEST(StepSpeed, ManualExampleRampIsExactly100PpsSquaredFrom12_5To100Pps) {
  StepCell c;
  c.table("SPD 5000\nDRV ADR,+,500,Ps\nGOTO NEXT\nMEND\n");
  c.run(2000);
  c.put("M1", 1);
  c.run(1000);
  ASSERT_TRUE(c.ax().moving());
  const uint64_t t0 = c.ax().start_ns();
  const auto at = [&](double s) { return t0 + static_cast<uint64_t>(std::llround(s * 1e9)); };
  const Trapezoid z = Trapezoid::of(500);
  ASSERT_DOUBLE_EQ(z.vp, 100);
  // Speed against virtual time: 12.5 pps at the start, +100 pps per second, 100 pps
  // after 0.875 s, and the mirror image at the end.
  EXPECT_DOUBLE_EQ(c.ax().frequency(t0), 12.5);
  EXPECT_NEAR(c.ax().frequency(at(0.5)), 62.5, 1e-6);
  EXPECT_NEAR((c.ax().frequency(at(0.6)) - c.ax().frequency(at(0.2))) / 0.4, kA, 1e-6);
  EXPECT_NEAR(c.ax().frequency(at(0.875)), 100, 1e-6);
  EXPECT_NEAR(c.ax().frequency(at(3.0)), 100, 1e-9);
  EXPECT_NEAR(c.ax().profile().peak(), 100, 1e-9);
  EXPECT_NEAR((c.ax().frequency(at(5.5)) - c.ax().frequency(at(5.0))) / 0.5, -kA, 1e-6);
  // The whole move: 2 x 0.875 s of ramps + 401.5625 steps at 100 pps = 5.765625 s.
  EXPECT_DOUBLE_EQ(z.duration(), 5.765625);
  EXPECT_EQ(c.ax().end_ns() - t0, 5765625000u);
  // Every pulse instant is the manual's ramp (within the 1 ns rounding of instants).
  for (int k : {1, 2, 10, 49, 50, 100, 300, 451, 452, 490, 499, 500})
    EXPECT_NEAR(static_cast<double>(c.ax().step_time(k, 1) - t0), z.time_at(k) * 1e9, 1.0) << k;
  // Pulses sent by an instant: travel is 12.5 t + 50 t^2 on the way up.
  EXPECT_EQ(c.ax().emitted(at(0.5)), 18);   // 6.25 + 12.5
  EXPECT_EQ(c.ax().emitted(at(0.875)), 49);  // 49.21875
  EXPECT_EQ(c.ax().emitted(c.ax().end_ns() - 1), 499);
  EXPECT_EQ(c.ax().emitted(c.ax().end_ns()), 500);
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 1; }, 7000000));
  EXPECT_EQ(c.done[0].t_ns, t0 + 5765625000u);
  EXPECT_EQ(c.get32("DR4088"), 500);
  EXPECT_EQ(c.get("M100"), 1u);
}

// A move shorter than both ramps peaks where they meet: v^2 = (V/8)^2 + A n.
TEST(StepSpeed, ShortMoveIsATriangleAtTheSameAcceleration) {
  StepCell c;
  c.table("SPD 5000\nDRV ADR,+,40,Ps\nGOTO NEXT\nMEND\n");
  c.run(2000);
  c.put("M1", 1);
  c.run(1000);
  const uint64_t t0 = c.ax().start_ns();
  const double vp = std::sqrt(12.5 * 12.5 + 100.0 * 40);  // 64.469 pps
  const double t_peak = (vp - 12.5) / 100;
  EXPECT_NEAR(c.ax().profile().peak(), vp, 1e-9);
  EXPECT_DOUBLE_EQ(c.ax().frequency(t0), 12.5);
  EXPECT_NEAR(c.ax().frequency(t0 + static_cast<uint64_t>(t_peak * 1e9)), vp, 1e-6);
  EXPECT_NEAR((c.ax().frequency(t0 + kSec / 10) - c.ax().frequency(t0)) / 0.1, 100, 1e-6);
  EXPECT_NEAR(static_cast<double>(c.ax().end_ns() - t0), 2 * t_peak * 1e9, 1.0);
  EXPECT_NEAR(static_cast<double>(c.ax().end_ns() - t0), Trapezoid::of(40).duration() * 1e9, 1.0);
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 1; }, 3000000));
  EXPECT_EQ(c.get32("DR4088"), 40);
  EXPECT_EQ(c.get("M100"), 1u);
}

// The full ramps cover 2 x 63/64 x 50 = 98.4375 steps: 99 steps reach 100 pps, 98 do not.
TEST(StepSpeed, FullSpeedNeedsTwice63_64OfTheAccelerationSteps) {
  for (const int n : {98, 99, 100}) {
    StepCell c;
    c.table("SPD 5000\nDRV ADR,+," + std::to_string(n) + ",Ps\nGOTO NEXT\nMEND\n");
    c.put("M1", 1);
    c.run(1000);
    const double expect = n >= 99 ? 100.0 : std::sqrt(12.5 * 12.5 + 100.0 * n);
    EXPECT_NEAR(c.ax().profile().peak(), expect, 1e-9) << n;
    EXPECT_NEAR(static_cast<double>(c.ax().end_ns() - c.ax().start_ns()), Trapezoid::of(n).duration() * 1e9, 1.0)
        << n;
  }
}

// STEPMOVE's relay: cleared when the move starts, set when the last pulse has been sent,
// at that instant.
TEST(StepSpeed, CompletionRelayClearedAtStartSetAtTheLastPulse) {
  StepCell c;
  c.table("SPD 5000\nDRV ADR,+,20,Ps\nGOTO NEXT\nMEND\n");
  c.put("M100", 1);  // left on by something earlier
  c.run(2000);
  EXPECT_EQ(c.get("M100"), 1u);  // nothing moved yet
  c.put("M1", 1);
  c.run(1000);
  EXPECT_EQ(c.get("M100"), 0u);
  const uint64_t t0 = c.ax().start_ns();
  const uint64_t end = c.ax().end_ns();
  EXPECT_NEAR(static_cast<double>(end - t0), Trapezoid::of(20).duration() * 1e9, 1.0);
  EXPECT_EQ(c.ax().step_time(20, 1), end);  // the last pulse's instant
  EXPECT_LT(c.ax().step_time(19, 1), end);
  c.clock_to(end - 1);
  EXPECT_EQ(c.get("M100"), 0u);
  EXPECT_TRUE(c.ax().moving());
  c.clock_to(end);
  EXPECT_EQ(c.get("M100"), 1u);
  EXPECT_EQ(c.ax().position(end), 20);
  ASSERT_FALSE(c.done.empty());
  EXPECT_EQ(c.done.back().t_ns, end);
}

// A stopped move has not sent its count: the relay stays off.
TEST(StepSpeed, AbortLeavesTheRelayOff) {
  StepCell c;
  c.table("SPD 5000\nDRV ADR,+,500,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(1000000);
  c.put("M3", 1);  // ABT, M1991 off: stop at once
  c.run(1000);
  EXPECT_FALSE(c.ax().moving());
  EXPECT_LT(c.get32("DR4088"), 500);
  c.run(10000000);
  EXPECT_EQ(c.get("M100"), 0u);
}

// Two FUN140 programs on the one axis: A (EN M1, ABT M3) and B (EN M4, ABT M6).
const char* const kTwoPrograms = R"(ORG M1925
MPARA Ps=0 SR=R2000 ERR=M13
ORG M1
LD M2
LD M3
HSPSO Ps=0 SR=R0 WR=R100 ACT=M10 ERR=M11 DN=M12
ORG M4
LD M5
LD M6
HSPSO Ps=0 SR=R300 WR=R400 ACT=M20 ERR=M21 DN=M22
END
)";

// A move started while one runs has no effect until it completes or is stopped.
TEST(StepSpeed, SecondStartIsIgnoredWhileMovingAcceptedAfterCompletion) {
  StepCell c(kYaml, kTwoPrograms);
  c.table("SPD 5000\nDRV ADR,+,500,Ps\nGOTO NEXT\nMEND\n", 0);
  c.table("SPD 5000\nDRV ADR,+,100,Ps\nGOTO NEXT\nMEND\n", 300);
  c.put("M1", 1);
  c.run(1000);
  const uint64_t end = c.ax().end_ns();
  c.run(1000000);
  c.put("M4", 1);  // B asks while A moves: nothing changes
  c.run(1000);
  EXPECT_EQ(c.ax().end_ns(), end);
  EXPECT_EQ(c.get("M20"), 0u);
  EXPECT_EQ(c.get("M100"), 0u);
  c.put("M4", 0);  // and gives up before A ends
  ASSERT_TRUE(c.run_until([&] { return c.get("M100") == 1; }, 6000000));
  c.run(5000);
  EXPECT_EQ(c.get32("DR4088"), 500);  // A only
  EXPECT_EQ(c.get("M100"), 1u);
  EXPECT_FALSE(c.ax().moving());
  c.put("M4", 1);  // after completion B starts
  c.run(1000);
  EXPECT_TRUE(c.ax().moving());
  EXPECT_EQ(c.get("M20"), 1u);
  EXPECT_EQ(c.get("M100"), 0u);
  ASSERT_TRUE(c.run_until([&] { return c.get("M100") == 1; }, 3000000));
  EXPECT_EQ(c.get32("DR4088"), 600);
}

TEST(StepSpeed, SecondStartIsAcceptedAfterAStop) {
  StepCell c(kYaml, kTwoPrograms);
  c.table("SPD 5000\nDRV ADR,+,500,Ps\nGOTO NEXT\nMEND\n", 0);
  c.table("SPD 5000\nDRV ADR,-,100,Ps\nGOTO NEXT\nMEND\n", 300);
  c.put("M1", 1);
  c.run(1000);
  c.run(1000000);
  c.put("M4", 1);
  c.run(1000);
  EXPECT_EQ(c.get("M20"), 0u);  // held off
  c.put("M3", 1);  // abort A: B (EN still on) is accepted now
  c.run(1000);
  const int64_t stopped_at = c.ax().position(c.ax().start_ns());
  EXPECT_TRUE(c.ax().moving());
  EXPECT_EQ(c.get("M20"), 1u);
  EXPECT_EQ(c.ax().direction(), -1);
  ASSERT_TRUE(c.run_until([&] { return c.get("M100") == 1; }, 3000000));
  EXPECT_EQ(c.get32("DR4088"), stopped_at - 100);
}

// The direction pin (Y1 for PSO0) is ON for a negative move, OFF for a positive one:
// the opposite of the FBs P/R direction pin.
TEST(StepSpeed, DirectionPinIsOnForNegativeMoves) {
  StepCell c;
  c.table("SPD 5000\nDRV ADR,-,30,Ps\nGOTO NEXT\nMEND\n");
  c.run(2000);
  EXPECT_EQ(c.get("Y1"), 0u);  // at rest before any move
  c.put("M1", 1);
  c.run(1000);
  ASSERT_TRUE(c.ax().moving());
  EXPECT_EQ(c.get("Y1"), 1u);
  const AxisSignal* pins = c.unit->pins(0);
  ASSERT_NE(pins, nullptr);
  EXPECT_TRUE(pins->levels(c.ax().start_ns() + kSec / 2).second);
  bool pulsed = false;
  for (int k = 1; k <= 30; ++k) pulsed = pulsed || pins->levels(pins->leading_edge(k)).first;
  EXPECT_TRUE(pulsed);
  ASSERT_TRUE(c.run_until([&] { return c.get("M100") == 1; }, 3000000));
  EXPECT_EQ(c.get32("DR4088"), -30);
  // Forward: OFF.
  c.table("SPD 5000\nDRV ADR,+,30,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1", 0);
  c.run(1000);
  c.put("M1", 1);
  c.run(1000);
  ASSERT_TRUE(c.ax().moving());
  EXPECT_EQ(c.get("Y1"), 0u);
  ASSERT_TRUE(c.run_until([&] { return c.get("M100") == 1; }, 3000000));
  EXPECT_EQ(c.get32("DR4088"), 0);
  // The same move on an axis without the form: ON = up (docs/motion.md "Pulse pins").
  StepCell plain("axes:\n  pso0: {output: PR}\n");
  plain.table("SPD 5000\nDRV ADR,+,30,Ps\nGOTO NEXT\nMEND\n");
  plain.put("M1", 1);
  plain.run(1000);
  ASSERT_TRUE(plain.ax().moving());
  EXPECT_EQ(plain.get("Y1"), 1u);
}

// An absolute move goes to the position relative to home (the FBs position, DR4088).
TEST(StepSpeed, AbsoluteMoveWorksOutCountAndDirectionFromThePosition) {
  StepCell c;
  c.table("SPD 5000\nDRV ABS,,-20,Ps\nGOTO NEXT\nMEND\n");
  c.put("DR4088", 50);  // the ladder sets home at 50 pulses before the move
  c.run(2000);
  c.put("M1", 1);
  c.run(1000);
  ASSERT_TRUE(c.ax().moving());
  EXPECT_EQ(c.get("Y1"), 1u);
  EXPECT_EQ(c.ax().profile().pulses(), 70);
  EXPECT_NEAR(static_cast<double>(c.ax().end_ns() - c.ax().start_ns()), Trapezoid::of(70).duration() * 1e9, 1.0);
  ASSERT_TRUE(c.run_until([&] { return c.get("M100") == 1; }, 3000000));
  EXPECT_EQ(c.get32("DR4088"), -20);
}

// A decelerated stop (M1991) slows at the same A to V/8.
TEST(StepSpeed, DeceleratedStopUsesTheStepRamp) {
  StepCell c;
  c.table("SPD 5000\nDRV ADR,+,500,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1991", 1);
  c.put("M1", 1);
  c.run(1000);
  const uint64_t t0 = c.ax().start_ns();
  c.run(2000000);  // at full speed
  c.put("M1", 0);  // EN off: stop, decelerating
  c.run(1000);
  const uint64_t ts = c.ax().start_ns();
  ASSERT_GT(ts, t0);
  EXPECT_NEAR(c.ax().frequency(ts), 100, 1e-6);
  EXPECT_NEAR((c.ax().frequency(ts + kSec / 2) - c.ax().frequency(ts)) / 0.5, -kA, 1e-6);
  ASSERT_TRUE(c.run_until([&] { return !c.ax().moving(); }, 2000000));
  EXPECT_EQ(c.get("M100"), 0u);  // stopped short of the count
}

// The tables the ROS services and the run action start (load_table/command) take the
// step ramp too; a start while the axis runs is refused; the abort ramps down at A.
TEST(StepSpeed, TablesRunOverRosUseTheStepRampAndTheLock) {
  StepCell c(kYaml, "END\n");
  c.run(1000);
  Table t;
  TableError e;
  ASSERT_TRUE(parse_table("SPD 5000\nDRV ADR,-,500,Ps\nGOTO NEXT\nMEND\n", &t, &e)) << e.message;
  std::string why;
  ASSERT_TRUE(c.with([&](MotionUnit& u) {
    return u.load_table(0, t, &why) && u.command(0, MotionUnit::Command::Start, &why);
  })) << why;
  const uint64_t t0 = c.ax().start_ns();
  EXPECT_DOUBLE_EQ(c.ax().frequency(t0), 12.5);
  EXPECT_EQ(c.ax().end_ns() - t0, 5765625000u);
  EXPECT_EQ(c.get("Y1"), 1u);  // backward
  c.run(2000000);
  EXPECT_FALSE(c.with([&](MotionUnit& u) { return u.command(0, MotionUnit::Command::Start, &why); }));
  EXPECT_EQ(c.ax().start_ns(), t0);
  ASSERT_TRUE(c.with([&](MotionUnit& u) { return u.command(0, MotionUnit::Command::Abort, &why); })) << why;
  const uint64_t ts = c.ax().start_ns();
  ASSERT_GT(ts, t0);
  EXPECT_NEAR(c.ax().frequency(ts), 100, 1e-6);
  EXPECT_NEAR((c.ax().frequency(ts + kSec / 4) - c.ax().frequency(ts)) / 0.25, -kA, 1e-6);
  ASSERT_TRUE(c.run_until([&] { return !c.ax().moving(); }, 2000000));
  EXPECT_EQ(c.get("M100"), 0u);
  // Accepted again once stopped.
  ASSERT_TRUE(c.with([&](MotionUnit& u) { return u.command(0, MotionUnit::Command::Start, &why); })) << why;
  EXPECT_TRUE(c.ax().moving());
  EXPECT_DOUBLE_EQ(c.ax().frequency(c.ax().start_ns()), 12.5);
}

// ---- configuration -------------------------------------------------------------------

std::string error_of(const std::string& yaml) {
  try {
    parse_axes_config(YAML::Load(yaml)["axes"], "cell.yaml");
  } catch (const SourceError& e) {
    return e.what();
  }
  return "";
}

TEST(StepSpeedConfig, ParsesTheForm) {
  const AxesConfig c = parse_axes_config(YAML::Load(kYaml)["axes"], "cell.yaml");
  const StepSpeed& s = c.axes[0].stepspeed;
  EXPECT_TRUE(s.used);
  EXPECT_EQ(s.pps, 100);
  EXPECT_EQ(s.accel_steps, 50);
  EXPECT_EQ(s.done, 100);
  EXPECT_DOUBLE_EQ(s.accel(), 100);
  EXPECT_DOUBLE_EQ(s.start_hz(), 12.5);
  EXPECT_FALSE(c.axes[1].stepspeed.used);
  // The limits themselves; done is optional; other params and output PR go with it.
  const AxesConfig d = parse_axes_config(YAML::Load(R"(axes:
  pso1:
    output: PR
    stepspeed: {pps: 10000, accel_steps: 2147483647}
    params: {at: R2000, p9: 0, p7: 4}
  pso2: {stepspeed: {pps: 1, accel_steps: 1, done: M1911}}
)")["axes"],
                                         "cell.yaml");
  EXPECT_EQ(d.axes[1].stepspeed.pps, 10000);
  EXPECT_EQ(d.axes[1].stepspeed.done, -1);
  EXPECT_EQ(d.axes[2].stepspeed.done, 1911);
}

TEST(StepSpeedConfig, BadValuesNameTheirLineAndWhy) {
  struct Case {
    const char* yaml;
    int line;
    const char* key;
    const char* why;
  };
  const Case cases[] = {
      {"axes:\n  pso0:\n    stepspeed: {pps: 0, accel_steps: 5}\n", 3, "axes.pso0.stepspeed.pps", "1-10000"},
      {"axes:\n  pso0:\n    stepspeed:\n      pps: 10001\n      accel_steps: 5\n", 4, "axes.pso0.stepspeed.pps",
       "1-10000"},
      {"axes:\n  pso0:\n    stepspeed:\n      pps: 100\n      accel_steps: 0\n", 5, "axes.pso0.stepspeed.accel_steps",
       "1-2147483647"},
      {"axes:\n  pso0:\n    stepspeed:\n      pps: 100\n      accel_steps: -3\n", 5,
       "axes.pso0.stepspeed.accel_steps", "1-2147483647"},
      {"axes:\n  pso0:\n    stepspeed:\n      pps: 100\n      accel_steps: 2147483648\n", 5,
       "axes.pso0.stepspeed.accel_steps", "1-2147483647"},
      {"axes:\n  pso0:\n    stepspeed:\n      pps: 1.5\n      accel_steps: 5\n", 4, "axes.pso0.stepspeed.pps", ""},
      {"axes:\n  pso0:\n    stepspeed: {accel_steps: 5}\n", 3, "axes.pso0.stepspeed", "needs pps"},
      {"axes:\n  pso0:\n    stepspeed: {pps: 5}\n", 3, "axes.pso0.stepspeed", "needs accel_steps"},
      {"axes:\n  pso0:\n    stepspeed: 100\n", 3, "axes.pso0.stepspeed", "expected {pps"},
      {"axes:\n  pso0:\n    stepspeed:\n      pps: 100\n      acc: 5\n", 5, "axes.pso0.stepspeed.acc", "unknown"},
      {"axes:\n  pso0:\n    stepspeed:\n      pps: 100\n      accel_steps: 5\n      done: Y3\n", 6,
       "axes.pso0.stepspeed.done", "M0-M1911"},
      {"axes:\n  pso0:\n    stepspeed:\n      pps: 100\n      accel_steps: 5\n      done: M1912\n", 6,
       "axes.pso0.stepspeed.done", "M0-M1911"},
      {"axes:\n  pso0:\n    stepspeed:\n      pps: 100\n      accel_steps: 5\n      done: R100\n", 6,
       "axes.pso0.stepspeed.done", "M0-M1911"},
      {"axes:\n  pso0:\n    stepspeed:\n      pps: 100\n      accel_steps: 5\n      done: M\n", 6,
       "axes.pso0.stepspeed.done", "M0-M1911"},
      // The keys it replaces, in either order, and a non-P/R output.
      {"axes:\n  pso0:\n    stepspeed: {pps: 100, accel_steps: 5}\n    params:\n      at: R2000\n      p8: 100\n", 6,
       "axes.pso0.params.p8", "conflicts with stepspeed"},
      {"axes:\n  pso0:\n    params:\n      at: R2000\n      p5: 20\n    stepspeed: {pps: 100, accel_steps: 5}\n", 5,
       "axes.pso0.params.p5", "conflicts with stepspeed"},
      {"axes:\n  pso0:\n    params: {at: R2000,\n      p4: 1000}\n    stepspeed: {pps: 100, accel_steps: 5}\n", 4,
       "axes.pso0.params.p4", "conflicts with stepspeed"},
      {"axes:\n  pso0:\n    stepspeed: {pps: 100, accel_steps: 5}\n    params:\n      at: R2000\n      p12: 10\n", 6,
       "axes.pso0.params.p12", "conflicts with stepspeed"},
      {"axes:\n  pso0:\n    output: UD\n    stepspeed: {pps: 100, accel_steps: 5}\n", 3, "axes.pso0.output",
       "needs output PR"},
      {"axes:\n  pso0:\n    stepspeed: {pps: 100, accel_steps: 5}\n    output: AB\n", 4, "axes.pso0.output",
       "needs output PR"},
  };
  for (const Case& k : cases) {
    const std::string e = error_of(k.yaml);
    EXPECT_NE(e.find("cell.yaml:" + std::to_string(k.line) + ":"), std::string::npos) << k.yaml << "\n" << e;
    EXPECT_NE(e.find(k.key), std::string::npos) << k.yaml << "\n" << e;
    EXPECT_NE(e.find(k.why), std::string::npos) << k.yaml << "\n" << e;
  }
}

// A rejected section changes nothing: the axis keeps the ramp it had.
TEST(StepSpeedConfig, RejectedConfigLeavesTheAxisAsItWas) {
  StepCell c;
  EXPECT_THROW(c.unit->configure(parse_axes_config(
                   YAML::Load("axes:\n  pso0: {stepspeed: {pps: 20000, accel_steps: 5}}\n")["axes"], "cell.yaml")),
               SourceError);
  EXPECT_EQ(c.unit->config().axes[0].stepspeed.pps, 100);
  c.table("SPD 5000\nDRV ADR,+,500,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(1000);
  EXPECT_EQ(c.ax().end_ns() - c.ax().start_ns(), 5765625000u);
}

// Without the form an axis runs FUN141's ramp as before: P5 start, P4/P8 slope.
TEST(StepSpeedConfig, AxesWithoutTheFormKeepFun141Ramp) {
  StepCell c("axes:\n  pso0: {output: PR}\n");
  c.table("SPD 5000\nDRV ADR,+,500,Ps\nGOTO NEXT\nMEND\n");
  c.put("M100", 1);
  c.put("M1", 1);
  c.run(1000);
  const uint64_t t0 = c.ax().start_ns();
  EXPECT_DOUBLE_EQ(c.ax().frequency(t0), 141);
  EXPECT_NEAR(c.ax().profile().peak(), 5000, 1e-9);
  ASSERT_TRUE(c.run_until([&] { return !c.ax().moving(); }, 1000000));
  EXPECT_EQ(c.get("M100"), 1u);  // no completion relay: M100 is the ladder's
  EXPECT_EQ(c.get32("DR4088"), 500);
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell
