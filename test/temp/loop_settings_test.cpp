// ~set_pid_loop's checks (temp::check_loop_change): a refused change names the field,
// its range and the value given, and writes nothing.
#include <gtest/gtest.h>

#include <cmath>

#include "plc_cell/core/memory.h"
#include "plc_cell/temp/loop_settings.h"

namespace plc_cell {
namespace temp {
namespace {

LoopDef oven(bool gains = true) {
  LoopDef l;
  l.name = "oven";
  l.sv = parse_address("R100");
  if (gains) {
    l.kc = parse_address("R120"), l.has_kc = true;
    l.ki = parse_address("R130"), l.has_ki = true;
    l.td = parse_address("R140"), l.has_td = true;
  }
  return l;
}

LoopChange sp(double v) {
  LoopChange c;
  c.setpoint = v;
  return c;
}

}  // namespace

TEST(LoopSettings, SetpointOutOfRangeNamesValueAndRange) {
  EXPECT_EQ(check_loop_change(oven(), sp(4000), false), "setpoint 4000.0 \u00b0C out of range -3276.8..3276.7 (NaN leaves it unchanged)");
  EXPECT_EQ(check_loop_change(oven(), sp(-3276.9), true), "setpoint -3276.9 \u00b0F out of range -3276.8..3276.7 (NaN leaves it unchanged)");
  EXPECT_EQ(check_loop_change(oven(), sp(3276.75), false).rfind("setpoint 3276.75 \u00b0C out of range", 0), 0u);
  EXPECT_NE(check_loop_change(oven(), sp(INFINITY), false).find("setpoint inf"), std::string::npos);
  // The ends of the 16-bit register in 0.1 degree are accepted; NaN means unchanged.
  EXPECT_EQ(check_loop_change(oven(), sp(3276.7), false), "");
  EXPECT_EQ(check_loop_change(oven(), sp(-3276.8), false), "");
  EXPECT_EQ(check_loop_change(oven(), sp(NAN), false), "");
}

TEST(LoopSettings, GainsOutOfRangeOrWithoutARegister) {
  LoopChange c;
  c.kc = 0;
  EXPECT_EQ(check_loop_change(oven(), c, false), "kc 0 out of range 1..9999 (-1 leaves it unchanged)");
  c.kc = 10000;
  EXPECT_EQ(check_loop_change(oven(), c, false), "kc 10000 out of range 1..9999 (-1 leaves it unchanged)");
  c = LoopChange();
  c.ki = -2;
  EXPECT_EQ(check_loop_change(oven(), c, false), "ki -2 out of range 0..9999 (-1 leaves it unchanged)");
  c = LoopChange();
  c.td = 12345;
  EXPECT_EQ(check_loop_change(oven(), c, false), "td 12345 out of range 0..9999 (-1 leaves it unchanged)");
  c = LoopChange();
  c.ki = 5;
  EXPECT_EQ(check_loop_change(oven(false), c, false),
            "ki 5: loop 'oven' has no ki register (give ki: in its modules.temperature.loops entry)");
  c.ki = -1;
  EXPECT_EQ(check_loop_change(oven(false), c, false), "");  // unchanged needs no register
  c.kc = 1, c.ki = 0, c.td = 9999;
  EXPECT_EQ(check_loop_change(oven(), c, false), "");
}

TEST(LoopSettings, ApplyWritesOnlyTheGivenFields) {
  Memory m;
  m.set_reg(Area::R, 120, 77);
  LoopChange c = sp(-12.34);
  c.ki = 25;
  ASSERT_EQ(check_loop_change(oven(), c, false), "");
  apply_loop_change(oven(), c, m);
  EXPECT_EQ(int16_t(m.reg(Area::R, 100)), -123);  // 0.1 degree, rounded
  EXPECT_EQ(m.reg(Area::R, 120), 77);             // kc -1: unchanged
  EXPECT_EQ(m.reg(Area::R, 130), 25);
  EXPECT_EQ(m.reg(Area::R, 140), 0);
}

}  // namespace temp
}  // namespace plc_cell
