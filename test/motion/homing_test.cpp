// DRVZ homing MD0/MD1/MD2 against positional DOG, limit and PG0 switches, in
// virtual time; the manual's Example 3 parameter table.
#include <algorithm>
#include <climits>
#include <cmath>

#include <yaml-cpp/yaml.h>

#include "motion_fixture.h"
#include "plc_cell/motion/axis_config.h"

namespace plc_cell {
namespace motion {
namespace {

constexpr double kA = 460000.0 / 0.1;
constexpr double kF0 = 141;

// Example 3's table (R500-R523) with P8 = 100 ms: DOG X2 (NO), limit X40 (NC),
// PG0 X4 front edge, CLR Y8, P16 = 100, P17 = 10, homing toward decreasing positions.
AxisParams example3() {
  AxisParams p;
  p.p8_acc_ms = 100;
  p.p9_home = 1;
  p.p15_io = 0x0804A802u;
  p.p16_zero = 100;
  p.p17_pg0 = 10;
  return p;
}

AxesConfig switches() {
  AxesConfig c;
  AxisDef& a = c.axes[0];
  a.used = true;
  a.name = "x";
  SwitchDef dog;
  dog.x = 2;
  dog.from = -5000;
  dog.to = -3000;
  SwitchDef limit;  // normally closed: on until the axis reaches -8000
  limit.x = 40;
  limit.from = -7999;
  SwitchDef pg0;
  pg0.x = 4;
  pg0.period = 200;
  pg0.width = 5;
  a.switches = {dog, limit, pg0};
  return c;
}

struct Homing : ::testing::Test {
  MotionCell c;
  void SetUp() override {
    c.params(example3());
    c.with([](MotionUnit& u) {
      u.configure(switches());
      return 0;
    });
  }
  std::vector<std::pair<uint64_t, bool>> clr;  // Y8 seen at the scans
  int64_t lo = INT64_MAX, hi = INT64_MIN;       // DR4088 range seen at the scans
  // P15 of Example 3 with one byte replaced (FFH: not configured).
  void io(uint32_t p15) {
    AxisParams p = example3();
    p.p15_io = p15;
    c.params(p);
  }
  void go(const std::string& mode, int64_t start = 0) {
    c.put("DR4088", static_cast<uint32_t>(start));
    c.run(1000);
    c.table("SPD 5000\nDRVZ " + mode + "\nGOTO NEXT\nMEND\n");
    c.put("M1", 1);
    ASSERT_TRUE(c.run_until(
        [&] {
          clr.push_back({c.now_us, c.get("Y8") != 0});
          if (c.done.empty()) {  // DR4088 at the scans until home (then it is P16)
            lo = std::min(lo, int64_t(c.get32("DR4088")));
            hi = std::max(hi, int64_t(c.get32("DR4088")));
          }
          return !c.done.empty();
        },
        20000000));
  }
  int64_t home_pulse_position() const { return -c.unit->axis(0).pulse_count(c.done[0].t_ns); }
  // Net pulses sent from the start to home (the position before P16 is loaded).
  int64_t net() const { return c.unit->axis(0).pulse_count(c.done[0].t_ns); }
};

// P15 bytes: DOG X2 NO = 02H, limit X40 NC = A8H, PG0 X4 front = 04H (rear = 84H),
// CLR Y8 = 08H; FFH = not configured.
constexpr uint32_t kNoClr = 0xFF04A802u, kNoPg0 = 0x08FFA802u, kNoLimit = 0x0804FF02u, kRear = 0x0884A802u;

TEST_F(Homing, Md2CountsTenPg0PulsesFromTheDogAndLoadsP16) {
  go("MD2");
  // DOG on at -3000; PG0 rising edges moving down at -3196, -3396, ... the 10th at -4996.
  EXPECT_EQ(home_pulse_position(), 4996);
  EXPECT_EQ(c.get32("DR4088"), 100);
  EXPECT_EQ(c.get("R4060"), 0u);
  // Closed form: seek at 5 kHz to -3000, decelerate to creep 1 kHz, creep to -4996, CLR 20 ms.
  const double ta = (5000 - kF0) / kA, sa = (5000.0 * 5000 - kF0 * kF0) / (2 * kA);
  const double t1 = ta + (3000 - sa) / 5000;
  const double td = 4000 / kA, sd = (5000.0 * 5000 - 1000.0 * 1000) / (2 * kA);
  const double t2 = td + (1996 - sd) / 1000;
  const double start = 1e-3;  // the scan that saw EN
  EXPECT_NEAR(c.done[0].t_ns * 1e-9, start + t1 + t2 + 0.020, 1e-7);
  // CLR (Y8) was on at the scans during those 20 ms, off after.
  int on = 0;
  for (const auto& s : clr) on += s.second;
  EXPECT_GE(on, 19);
  EXPECT_LE(on, 21);
  EXPECT_EQ(c.get("Y8"), 0u);
}

TEST_F(Homing, Md0HomesWhereTheAxisLeavesTheDog) {
  go("MD0");
  EXPECT_EQ(home_pulse_position(), 5001);
  EXPECT_EQ(c.get32("DR4088"), 100);
}

TEST_F(Homing, Md1StopsOnTheDogWaitsHalfASecondAndBacksOut) {
  go("MD1");
  // Decelerated stop from 5 kHz entering the DOG at -3000, then back up at creep
  // speed until it leaves the DOG at -2999.
  EXPECT_EQ(c.unit->axis(0).pulse_count(c.done[0].t_ns), -2999);  // net pulses from 0
  EXPECT_EQ(c.get32("DR4088"), 100);
}

TEST_F(Homing, StartBeyondTheDogUsesTheLimitAndComesBack) {
  go("MD0", -6000);
  // Down to the limit (-8000), up through the DOG (leaves it at -2999), down again,
  // creep through the DOG: home at -5001.
  EXPECT_EQ(c.unit->axis(0).pulse_count(c.done[0].t_ns), -5001 + 6000);  // net pulses from -6000
  EXPECT_EQ(c.get32("DR4088"), 100);
}

TEST_F(Homing, MissingDogIsCode51AndNothingMoves) {
  AxisParams p = example3();
  p.p15_io = 0xFFFFFFFFu;
  c.params(p);
  c.table("SPD 5000\nDRVZ MD0\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(10000);
  EXPECT_EQ(c.get("R4060"), 51u);
  EXPECT_EQ(c.get32("DR4088"), 0);
  p.p15_io = 0xFFFFA802u;  // no PG0 for MD2
  c.params(p);
  c.table("SPD 5000\nDRVZ MD2\nGOTO NEXT\nMEND\n");
  c.put("M1", 0);
  c.run(1000);
  c.put("M1", 1);
  c.run(10000);
  EXPECT_EQ(c.get("R4060"), 52u);
}

// ---- no CLR output (P15-3 = FFH): "the zero return process has been finished at step c" ----

TEST_F(Homing, NoClrMd0IsDoneWhereTheAxisLeavesTheDog) {
  io(kNoClr);
  go("MD0");
  EXPECT_EQ(net(), -5001);  // the DOG spans -5000..-3000: off again at -5001
  EXPECT_EQ(c.get32("DR4088"), 100);
  EXPECT_EQ(c.get("R4060"), 0u);
  EXPECT_EQ(c.get("M1996"), 1u);
  for (const auto& s : clr) EXPECT_FALSE(s.second);  // Y8 is no CLR here: never touched
}

TEST_F(Homing, NoClrMd1IsDoneWhereTheAxisBacksOutOfTheDog) {
  io(kNoClr);
  go("MD1");
  EXPECT_EQ(net(), -2999);  // stopped inside the DOG, back up until off at -2999
  EXPECT_EQ(c.get32("DR4088"), 100);
  EXPECT_EQ(c.get("M1996"), 1u);
}

TEST_F(Homing, NoClrMd2IsDoneAtTheTenthPg0EdgeWithoutTheTwentyMs) {
  io(kNoClr);
  go("MD2");
  EXPECT_EQ(net(), -4996);  // as with CLR: the 10th rising PG0 edge after -3000
  EXPECT_EQ(c.get32("DR4088"), 100);
  EXPECT_EQ(c.get("M1996"), 1u);
  // The same closed form as with CLR, without the 20 ms pulse.
  const double ta = (5000 - kF0) / kA, sa = (5000.0 * 5000 - kF0 * kF0) / (2 * kA);
  const double t1 = ta + (3000 - sa) / 5000;
  const double td = 4000 / kA, sd = (5000.0 * 5000 - 1000.0 * 1000) / (2 * kA);
  const double t2 = td + (1996 - sd) / 1000;
  EXPECT_NEAR(c.done[0].t_ns * 1e-9, 1e-3 + t1 + t2, 1e-7);
}

// ---- PG0 and the limit are optional where the manual says so ----

TEST_F(Homing, Md0NeedsNoPg0) {
  io(kNoPg0);
  go("MD0");
  EXPECT_EQ(net(), -5001);
  EXPECT_EQ(c.get("R4060"), 0u);
}

TEST_F(Homing, Md1NeedsNoPg0) {
  io(kNoPg0);
  go("MD1");
  EXPECT_EQ(net(), -2999);
  EXPECT_EQ(c.get("R4060"), 0u);
}

TEST_F(Homing, Md2RearEdgeCountsPg0FromLeavingTheDog) {
  io(kRear);
  go("MD2");
  // Off the DOG at -5001; PG0 is on for pos mod 200 in 0..4, so moving down its rising
  // edges are at -5196, -5396, ...; the 10th at -5196 - 9 x 200 = -6996.
  EXPECT_EQ(net(), -6996);
  EXPECT_EQ(c.get32("DR4088"), 100);
}

TEST_F(Homing, BehindTheDogTheLimitIsNotNeeded) {
  io(kNoLimit);
  go("MD2");
  EXPECT_EQ(net(), -4996);
}

// ---- started on the DOG: to the limit, back until off the DOG, then the normal run ----

TEST_F(Homing, OnTheDogMd0GoesToTheLimitFirst) {
  go("MD0", -4000);
  // Down at 5 kHz past the DOG's edge (-5000) to the limit (acts at -8000): 4000 pulses;
  // up through the DOG until off it at -2999: 5001; down, creep from -3000, off at -5001:
  // 2002. Net -1001; never beyond the limit.
  EXPECT_EQ(net(), -5001 + 4000);
  EXPECT_EQ(c.get32("DR4088"), 100);
  // Scans every 1 ms at 5 kHz see the reversal at -8000 within 5 pulses; never beyond.
  EXPECT_GE(lo, -8000);
  EXPECT_LE(lo, -7995);
  EXPECT_LE(hi, -2999);
}

TEST_F(Homing, OnTheDogMd2CountsFromTheDogsFrontEdgeNotFromTheStart) {
  go("MD2", -4000);
  // Counting starts on entering the DOG at -3000 on the final run: home at -4996, as
  // from behind the DOG (counting from the start point would give -5996).
  EXPECT_EQ(net(), -4996 + 4000);
  EXPECT_EQ(c.get32("DR4088"), 100);
}

TEST_F(Homing, OnTheDogMd1StopsOnTheDogAfterComingBack) {
  go("MD1", -4000);
  // Limit, back out of the DOG at -2999, toward home again: stop on the DOG, 0.5 s,
  // back up until off it at -2999.
  EXPECT_EQ(net(), -2999 + 4000);
  EXPECT_LE(lo, -7995);  // it went to the limit first
}

TEST_F(Homing, OnTheDogWithoutLimitLeavesTheDogBackwardFirst) {
  io(kNoLimit);
  go("MD0", -4000);
  // No limit to go to: up at SPD until off the DOG at -2999, then the normal run.
  EXPECT_EQ(net(), -5001 + 4000);
  // It never went toward home before the final run: up to -2999, down to -5001 only.
  EXPECT_GE(lo, -5001);
  EXPECT_LE(hi, -2999);
  EXPECT_GE(hi, -3004);
}

TEST_F(Homing, OnTheDogWithoutLimitMd2CountsFromTheFrontEdge) {
  io(kNoLimit);
  go("MD2", -4000);
  EXPECT_EQ(net(), -4996 + 4000);
}

// ---- started beyond the DOG (between the DOG and the limit) ----

TEST_F(Homing, BeyondTheDogMd2UsesTheLimit) {
  go("MD2", -6000);
  // Down to -8000, up off the DOG at -2999, down: 10th PG0 edge at -4996.
  EXPECT_EQ(net(), -4996 + 6000);
}

TEST_F(Homing, StartedOnTheLimitBacksOutThroughTheDog) {
  go("MD0", -8500);
  // The limit is active at once: up through the DOG (off at -2999), down, off at -5001.
  EXPECT_EQ(net(), -5001 + 8500);
}

TEST_F(Homing, BeyondTheDogWithoutLimitRunsTowardHomeUntilStopped) {
  // The PLC cannot know it is past the DOG: it keeps seeking, as the real unit does,
  // until EN goes off. No error, no home.
  io(kNoLimit);
  c.put("DR4088", static_cast<uint32_t>(-6000));
  c.run(1000);
  c.table("SPD 5000\nDRVZ MD0\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(2000000);
  EXPECT_TRUE(c.done.empty());
  EXPECT_EQ(c.get("R4060"), 0u);
  EXPECT_EQ(c.get("M1992"), 0u);  // the axis is busy
  EXPECT_LT(c.get32("DR4088"), -6000 - 9000);  // about 2 s at 5 kHz toward decreasing
  c.put("M1", 0);
  c.run(2000);
  EXPECT_EQ(c.get("M1992"), 1u);
  const int32_t stopped = c.get32("DR4088");
  c.run(100000);
  EXPECT_EQ(c.get32("DR4088"), stopped);
  EXPECT_EQ(c.get("M1996"), 0u);
}

// ---- a counter on the pins agrees with where the axis homed ----

TEST(HomingWired, CounterOnThePinsCountsTheHomedTravel) {
  struct Case {
    const char* mode;
    int64_t start, home;  // home: the switch edge computed by hand above
  };
  for (const Case k : {Case{"MD2", -4000, -4996}, Case{"MD0", -4000, -5001}, Case{"MD2", 0, -4996},
                       Case{"MD1", -6000, -2999}}) {
    const std::string yaml =
        "counters:\n  hsc0: {mode: MD1, b: true}\n"
        "axes:\n  pso0:\n    output: UD\n    wiring: {Y0: X0, Y1: X1}\n    switches:\n"
        "      - {x: X2, from: -5000, to: -3000}\n      - {x: X40, from: -7999}\n"
        "      - {x: X4, period: 200, width: 5}\n";
    MotionCell c(kAxis0Program, true, hsc::parse_hsc_config(YAML::Load(yaml)["counters"], "cell.yaml"));
    c.unit->configure(parse_axes_config(YAML::Load(yaml)["axes"], "cell.yaml"));
    AxisParams p = example3();
    p.p15_io = kNoClr;
    c.params(p);
    c.put("DR4088", static_cast<uint32_t>(k.start));
    c.run(1000);
    c.table(std::string("SPD 5000\nDRVZ ") + k.mode + "\nGOTO NEXT\nMEND\n");
    c.put("M1", 1);
    ASSERT_TRUE(c.run_until([&] { return !c.done.empty(); }, 20000000)) << k.mode << " " << k.start;
    c.run(2000);
    const int64_t cv = c.plc.locked([&](ScanEngine&, Memory&) { return c.counters->count(0); });
    // HSC0 MD1 counts both edges of every U (+) and D (-) pulse: 2 per pulse.
    EXPECT_EQ(cv, 2 * (k.home - k.start)) << k.mode << " from " << k.start;
    EXPECT_EQ(c.get32("DR4088"), 100) << k.mode;
  }
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell
