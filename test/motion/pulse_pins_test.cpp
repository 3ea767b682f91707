// The pins Y0-Y7 of the pulse axes in virtual time (U/D, P/R, A/B, polarity), the
// Y image of configured axes, and the axes wired into the high-speed counters:
// the output pins looped back to inputs, and an encoder on the load
// (docs/motion.md "Pulse pins", "Wiring into the counters").
#include <yaml-cpp/yaml.h>

#include <cmath>

#include "motion_fixture.h"
#include "plc_cell/core/error.h"
#include "plc_cell/timeline/scheduler.h"
#include "plc_cell/motion/pulse_pins.h"

namespace plc_cell {
namespace motion {
namespace {

constexpr uint64_t kMs = 1000000;

// A move of 5 pulses at a constant 1 kHz from t = 0: pulse k ends at k ms.
Axis constant_move(bool forward) {
  Axis a;
  a.start(0, forward ? 5 : -5, 0, forward, Profile::plan(5, 1000, 1000, 1000, kInf, kInf));
  return a;
}

TEST(PulsePins, PrPulsesHalfAPeriodEndingAtEachPulseInstant) {
  const Axis a = constant_move(true);
  const AxisSignal s = AxisSignal::pins("p", &a, OutputMode::PR, Polarity::NormalOff);
  // Pulse k is ON for travel in [k - 1/2, k): 0.5-1 ms, 1.5-2 ms, ...; R = ON (up).
  const std::pair<uint64_t, bool> y0[] = {{0, false},          {kMs / 4, false}, {kMs / 2, true},
                                          {3 * kMs / 4, true}, {kMs, false},     {kMs + kMs / 2, true},
                                          {5 * kMs, false},    {9 * kMs, false}};
  for (const auto& e : y0) {
    EXPECT_EQ(s.levels(e.first).first, e.second) << e.first;
    EXPECT_TRUE(s.levels(e.first).second) << e.first;
  }
  EXPECT_EQ(s.leading_edge(3), 2 * kMs + kMs / 2);
  EXPECT_EQ(s.trailing_edge(3), 3 * kMs);
  EXPECT_EQ(s.next_edge(kMs), kMs + kMs / 2);
  EXPECT_EQ(s.next_edge(kMs + kMs / 2), 2 * kMs);
  const Axis b = constant_move(false);
  const AxisSignal r = AxisSignal::pins("p", &b, OutputMode::PR, Polarity::NormalOff);
  EXPECT_FALSE(r.levels(kMs / 4).second);  // R = OFF: down
  EXPECT_TRUE(r.levels(3 * kMs / 4).first);
}

TEST(PulsePins, UdPulsesOnTheUpOrDownPinOnly) {
  const Axis f = constant_move(true), b = constant_move(false);
  const AxisSignal up = AxisSignal::pins("p", &f, OutputMode::UD, Polarity::NormalOff);
  const AxisSignal down = AxisSignal::pins("p", &b, OutputMode::UD, Polarity::NormalOff);
  for (uint64_t t = 0; t < 6 * kMs; t += kMs / 8) {
    const bool pulse = (t % kMs) >= kMs / 2 && t < 5 * kMs;
    EXPECT_EQ(up.levels(t).first, pulse) << t;
    EXPECT_FALSE(up.levels(t).second) << t;
    EXPECT_FALSE(down.levels(t).first) << t;
    EXPECT_EQ(down.levels(t).second, pulse) << t;
  }
}

TEST(PulsePins, AbQuadratureALeadsForwardAndLagsBackward) {
  const Axis f = constant_move(true), b = constant_move(false);
  const AxisSignal fw = AxisSignal::pins("p", &f, OutputMode::AB, Polarity::NormalOff);
  const AxisSignal bw = AxisSignal::pins("p", &b, OutputMode::AB, Polarity::NormalOff);
  // Forward, per pulse: (A,B) = (0,1) rest, (0,0) from 1/4, (1,0) from 1/2, (1,1) from 3/4.
  const bool fa[] = {false, false, true, true}, fb[] = {true, false, false, true};
  // Backward just after the same instants: (1,1), (1,0), (0,0), (0,1): A falls after 1/2.
  const bool ba[] = {true, true, false, false}, bb[] = {true, false, false, true};
  for (int i = 0; i < 4; ++i) {
    const uint64_t t = kMs + i * kMs / 4 + 1000;  // inside pulse 2
    EXPECT_EQ(fw.levels(t).first, fa[i]) << i;
    EXPECT_EQ(fw.levels(t).second, fb[i]) << i;
    EXPECT_EQ(bw.levels(t).first, ba[i]) << i;
    EXPECT_EQ(bw.levels(t).second, bb[i]) << i;
  }
  EXPECT_FALSE(fw.levels(5 * kMs).first);  // rest: A off, B on
  EXPECT_TRUE(fw.levels(5 * kMs).second);
}

TEST(PulsePins, NormalOnInvertsThePulsePinsNotTheDirection) {
  const Axis a = constant_move(true);
  const AxisSignal s = AxisSignal::pins("p", &a, OutputMode::PR, Polarity::NormalOn);
  EXPECT_TRUE(s.levels(0).first);  // idle level ON
  EXPECT_FALSE(s.levels(3 * kMs / 4).first);
  EXPECT_TRUE(s.levels(3 * kMs / 4).second);  // direction stays ON = up
  const AxisSignal u = AxisSignal::pins("p", &a, OutputMode::UD, Polarity::NormalOn);
  EXPECT_TRUE(u.levels(kMs / 4).second);  // the idle D pin rests ON too
}

TEST(PulsePins, EdgesOfARampedMoveComeFromTheProfilesInverse) {
  Axis a;
  const Profile p = Profile::plan(1000000, 141, 921600, 141, 4.6e6, 4.6e6);
  a.start(7, 1000000, 0, true, p);
  const AxisSignal s = AxisSignal::pins("p", &a, OutputMode::PR, Polarity::NormalOff);
  for (int64_t k : {1, 2, 1000, 123457, 999999, 1000000}) {
    // Leading edge at travel k - 1/2, trailing at k, rounded up to the ns.
    EXPECT_EQ(s.leading_edge(k), 7 + static_cast<uint64_t>(std::ceil(p.time_of(k - 0.5) * 1e9 - 1e-6))) << k;
    EXPECT_TRUE(s.levels(s.leading_edge(k)).first) << k;
    EXPECT_FALSE(s.levels(s.leading_edge(k) - 1).first) << k;
    EXPECT_FALSE(s.levels(s.trailing_edge(k)).first) << k;
  }
  EXPECT_EQ(s.trailing_edge(1000000), a.end_ns());
  EXPECT_EQ(s.leading_edge(1000001), kNever);
}

// A cut keeps a pulse whose leading edge has left the pin, so a counter on the pin
// and the position agree whatever the instant of the cut.
TEST(PulsePins, ACutCompletesAPulseWhoseEdgeIsOut) {
  for (uint64_t t : {kMs + kMs / 2 - 1, kMs + kMs / 2, 2 * kMs - 1}) {
    Axis a = constant_move(true);
    a.cut(t);
    EXPECT_EQ(a.pulse_count(t), t >= kMs + kMs / 2 ? 2 : 1) << t;
  }
}

// ---- the cell: Y image and wiring -------------------------------------------------

class WiredCell : public MotionCell {
 public:
  WiredCell(const std::string& yaml, const std::string& il) : MotionCell(il, true, hsc_config(yaml)) {
    unit->configure(parse_axes_config(YAML::Load(yaml)["axes"], "cell.yaml"));
  }
  static hsc::HscConfig hsc_config(const std::string& yaml) {
    return hsc::parse_hsc_config(YAML::Load(yaml)["counters"], "cell.yaml");
  }
  int64_t cv(int n) {
    return plc.locked([&](ScanEngine&, Memory&) { return counters->count(n); });
  }
};

// Ladder: FUN141/FUN140 on PSO0 (kAxis0Program without its END), and Y0, Y1, Y2 set
// by the ladder all along.
const std::string kLadderY = std::string(kAxis0Program).substr(0, std::string(kAxis0Program).rfind("END")) +
                             "ORG M1925\nOUT Y0\nOUT Y1\nOUT Y2\nEND\n";

TEST(PulsePins, ConfiguredAxisOwnsItsPinsTheLadderDoesNotReachThem) {
  WiredCell c("axes:\n  pso0: {output: PR}\n", kLadderY);
  std::vector<std::pair<uint64_t, uint32_t>> seen;
  c.counters->on_output([&](uint64_t t, uint32_t y, bool v) {
    if (v) seen.push_back({t, y});
  });
  c.params(fast_params());
  c.table("SPD 1000\nDRV ADR,+,3,Ps\nGOTO NEXT\nMEND\n");
  c.run(5000, 1000);
  EXPECT_EQ(c.get("Y0"), 0u);  // the pin's level (idle, normal OFF), not the relay
  EXPECT_EQ(c.get("Y1"), 1u);  // the direction pin: ON = up (nothing has moved yet)
  EXPECT_EQ(c.get("Y2"), 1u);  // PSO1 not configured: an ordinary output
  for (const auto& s : seen) EXPECT_NE(s.second, 0u) << "Y0 reached the terminal at " << s.first;
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].second, 2u);
  // During the move the Y image shows the pin at the scan instant: pulses are 1 ms,
  // ON for the second half; scans at 0.25 ms steps see ON then OFF.
  c.put("M1", 1);
  std::vector<uint32_t> y0;
  for (int i = 0; i < 16; ++i) {
    c.run(250, 250);
    y0.push_back(c.get("Y0"));
  }
  int on = 0;
  for (uint32_t v : y0) on += v;
  EXPECT_GE(on, 5);  // 3 pulses x 2 samples of the ON half (ramp-free at 1 kHz: P5 = 141 Hz start)
  EXPECT_EQ(c.get32("DR4088"), 3);
}

TEST(PulsePins, YamlPolarityNormalOnIdlesThePinsInverted) {
  // PSO1 owns Y2/Y3 (the ladder does not write them). A/B at rest is A off, B on.
  for (const char* pol : {"normal_off", "normal_on"}) {
    WiredCell c(std::string("axes:\n  pso1: {output: AB, polarity: ") + pol + "}\n", kAxis0Program);
    c.run(3000);
    const bool inverted = std::string(pol) == "normal_on";
    EXPECT_EQ(c.get("Y2"), inverted ? 1u : 0u) << pol;
    EXPECT_EQ(c.get("Y3"), inverted ? 0u : 1u) << pol;
  }
}

TEST(PulsePins, UnconfiguredAxisLeavesY0Y1ToTheLadder) {
  WiredCell c("axes:\n  pso0: {name: slide}\n", kLadderY);
  c.run(3000);
  EXPECT_EQ(c.get("Y0"), 1u);
  EXPECT_EQ(c.get("Y1"), 1u);
}

// Y0/Y1 looped back into HSC0 (X0/X1): every pulse of a ramped move is counted.
struct LoopCase {
  const char* output;
  const char* counter;
  int64_t per_pulse;  // counts per pulse, forward (hand: the counting rule of the mode)
};

int64_t run_loop(const LoopCase& lc, int64_t* after_back) {
  const std::string yaml = std::string("counters:\n  hsc0: ") + lc.counter +
                           "\naxes:\n  pso0: {output: " + lc.output + ", wiring: {Y0: X0, Y1: X1}}\n";
  WiredCell c(yaml, kAxis0Program);
  c.params(fast_params());  // P8 = 100 ms: ramps of 141 Hz -> 50 kHz over 10,000+ pulses
  c.table("SPD 50000\nDRV ADR,+,123457,Ps\nGOTO NEXT\nSPD 20000\nDRV ADR,-,23457,Ps\nGOTO NEXT\nMEND\n");
  int64_t after_fwd = 0;
  c.unit->on_step_done([&](int, int step, uint64_t) {
    if (step == 1) after_fwd = c.counters->count(0);
  });
  c.put("M1", 1);
  EXPECT_TRUE(c.run_until([&] { return c.get("M1996") == 1; }, 20000000, 1700));
  *after_back = c.cv(0);
  return after_fwd;
}

TEST(PulsePins, LoopbackCountsEveryPulseOfARampedMoveInEachMode) {
  const LoopCase cases[] = {
      {"UD", "{mode: MD0, b: true}", 1},                   // U +1, D -1
      {"UD", "{mode: MD1, b: true}", 2},                   // both edges
      {"PR", "{mode: MD2, b: true, invert: [count]}", 1},  // R = inverted Y1: ON = up -> R = 0 -> +1
      {"PR", "{mode: MD2, b: true}", -1},                  // Y1 ON (up) is R = 1: counts down
      {"PR", "{mode: MD3, b: true, invert: [count]}", 2},
      {"AB", "{mode: MD4}", 1},
      {"AB", "{mode: MD7}", 4},
  };
  for (const auto& lc : cases) {
    int64_t back = 0;
    const int64_t fwd = run_loop(lc, &back);
    EXPECT_EQ(fwd, 123457 * lc.per_pulse) << lc.output << " " << lc.counter;
    EXPECT_EQ(back, 100000 * lc.per_pulse) << lc.output << " " << lc.counter;
  }
}

TEST(PulsePins, EncoderOnTheLoadCountsPeriodsPerPulseAndBacklash) {
  // 2 A/B periods per pulse into HSC1 x4: 8 counts per pulse. Backlash 30 and
  // backward compensation 5: the backward move emits 35 more pulses than its stroke.
  WiredCell c("counters:\n  hsc1: {mode: MD7}\naxes:\n  pso0: {encoder: {a: X4, b: X5, periods_per_pulse: 2}}\n",
              kAxis0Program);
  AxisParams p = fast_params();
  p.p7_backlash = 30;
  p.p11_bwd_comp = 5;
  c.params(p);
  c.table("SPD 30000\nDRV ADR,+,40000,Ps\nGOTO NEXT\nSPD 30000\nDRV ADR,-,10000,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.get("M1996") == 1; }, 20000000, 900));
  EXPECT_EQ(c.get32("DR4088"), 30000);
  EXPECT_EQ(c.cv(1), 8 * (40000 - 10035));
}

// CV=PV of a software counter on the looped-back U pin interrupts at the leading
// edge of pulse PV, within one pulse period of the profile's instant of pulse PV.
TEST(PulsePins, CvEqualsPvInterruptsAtTheEdgeOfThatPulse) {
  const std::string il = std::string(kAxis0Program) + "LBL HSC4I\nORG M1925\nINC D=R300\nRTI\n";
  WiredCell c("counters:\n  hsc4: {mode: MD0, a: X0, b: X1}\naxes:\n  pso0: {output: UD, wiring: {Y0: X0, Y1: X1}}\n",
              il);
  c.params(fast_params());
  c.table("SPD 40000\nDRV ADR,+,30000,Ps\nGOTO NEXT\nMEND\n");
  const int64_t pv = 100;  // inside the ramp: 141 Hz -> 40 kHz at 4.6 MHz/s takes 174 pulses
  c.put("DR" + std::to_string(hsc::pv_register(4)), pv);
  c.put("M1", 1);
  c.run(1000);
  const Axis ax = c.with([](MotionUnit& u) { return u.axis(0); });
  ASSERT_TRUE(ax.moving());
  const AxisSignal pins = AxisSignal::pins("p", &ax, OutputMode::UD, Polarity::NormalOff);
  ASSERT_TRUE(c.run_until([&] { return c.get("M1996") == 1; }, 5000000));
  std::vector<uint64_t> at;
  for (const auto& i : c.isrs)
    if (i.second == hsc::kHsc4I) at.push_back(i.first);
  ASSERT_EQ(at.size(), 1u);
  EXPECT_EQ(at[0], pins.leading_edge(pv));
  const double t_pulse = ax.start_ns() * 1e-9 + ax.profile().time_of(double(pv));
  EXPECT_LT(std::fabs(at[0] * 1e-9 - t_pulse), 1.0 / ax.profile().velocity(t_pulse - ax.start_ns() * 1e-9));
  EXPECT_EQ(c.get("R300"), 1u);
  EXPECT_EQ(c.cv(4), 30000);
}

// Immediate stops at arbitrary instants: the counter on the pins equals the position.
TEST(PulsePins, AbortAtAnyInstantCountAndPositionAgree) {
  for (uint64_t period : {997u, 1003u, 1500u}) {
    WiredCell c("counters:\n  hsc0: {mode: MD1, b: true}\naxes:\n  pso0: {output: UD, wiring: {Y0: X0, Y1: X1}}\n",
                kAxis0Program);
    c.params(fast_params());
    c.table("SPD 3000\nDRV ADR,+,100000,Ps\nGOTO NEXT\nMEND\n");
    c.put("M1", 1);
    c.run(50 * period, period);
    c.put("M3", 1);  // ABT, M1991 off: immediate
    c.run(5 * period, period);
    const int32_t pos = c.get32("DR4088");
    EXPECT_GT(pos, 0);
    EXPECT_EQ(c.cv(0), 2 * pos) << period;  // MD1: both edges of every pulse
  }
}

TEST(PulsePins, WiringErrorsNameTheLine) {
  const auto fails = [](const std::string& yaml, const std::string& what) {
    try {
      WiredCell c(yaml, kAxis0Program);
      ADD_FAILURE() << "no error for " << yaml;
    } catch (const SourceError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  fails("axes:\n  pso0:\n    output: PR\n    wiring: {Y2: X0}\n", "cell.yaml:4");
  fails("axes:\n  pso0:\n    output: PR\n    wiring: {Y0: X20}\n", "X0-X15");
  fails("axes:\n  pso0:\n    polarity: inverted\n", "normal_off or normal_on");
  fails("axes:\n  pso0:\n    wiring: {Y0: X0}\n", "with `output:`");
  fails("counters:\n  sources:\n    - {name: enc, a: X4, hz: 10}\naxes:\n  pso0:\n    encoder: {a: X4, b: X5}\n",
        "cell.yaml:6");
  fails("axes:\n  pso0:\n    encoder: {a: X4, periods_per_pulse: 0}\n", "1-1000");
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell
