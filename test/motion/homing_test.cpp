// DRVZ homing MD0/MD1/MD2 against positional DOG, limit and PG0 switches, in
// virtual time; the manual's Example 3 parameter table.
#include <cmath>

#include "motion_fixture.h"

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
  void go(const std::string& mode, int64_t start = 0) {
    c.put("DR4088", static_cast<uint32_t>(start));
    c.run(1000);
    c.table("SPD 5000\nDRVZ " + mode + "\nGOTO NEXT\nMEND\n");
    c.put("M1", 1);
    ASSERT_TRUE(c.run_until(
        [&] {
          clr.push_back({c.now_us, c.get("Y8") != 0});
          return !c.done.empty();
        },
        20000000));
  }
  int64_t home_pulse_position() const { return -c.unit->axis(0).pulse_count(c.done[0].t_ns); }
};

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

}  // namespace
}  // namespace motion
}  // namespace plc_cell
