// Conditions as docs/testing-your-cell.md defines them ("What a condition reads").
#include <gtest/gtest.h>

#include "plc_cell/core/error.h"
#include "plc_cell/scenario/condition.h"

using namespace plc_cell;
using namespace plc_cell::scenario;

namespace {

Reading num(double v) {
  Reading r;
  r.number = v;
  return r;
}

}  // namespace

TEST(ScenarioCondition, BareNameIsOnNotNameIsOff) {
  const Condition on = parse_condition("Y0");
  ASSERT_EQ(on.all.size(), 1u);
  EXPECT_TRUE(on.all[0].holds(num(1)));
  EXPECT_FALSE(on.all[0].holds(num(0)));
  for (const char* t : {"not Y0", "!Y0", "! Y0"}) {
    const Condition off = parse_condition(t);
    EXPECT_TRUE(off.all[0].holds(num(0))) << t;
    EXPECT_FALSE(off.all[0].holds(num(1))) << t;
  }
}

TEST(ScenarioCondition, ComparisonsJoinedByAnd) {
  const Condition c = parse_condition("R0 >= 3 and conveyor_run and DR10:u < 0x10");
  ASSERT_EQ(c.all.size(), 3u);
  EXPECT_EQ(c.all[0].probe.name, "R0");
  EXPECT_EQ(c.all[0].op, Comparison::Op::Ge);
  EXPECT_EQ(c.all[2].probe.format, ValueFormat::Unsigned);
  EXPECT_EQ(c.all[2].value, 16);
  EXPECT_TRUE(c.all[0].holds(num(3)));
  EXPECT_FALSE(c.all[0].holds(num(2)));
}

TEST(ScenarioCondition, ToleranceAndTemperatureUnit) {
  const Condition c = parse_condition("temperature.oven_temp == 200 C +- 1.5");
  ASSERT_EQ(c.all.size(), 1u);
  EXPECT_EQ(c.all[0].probe.kind, Probe::Kind::Temperature);
  EXPECT_EQ(c.all[0].value, 200);
  EXPECT_EQ(c.all[0].tolerance, 1.5);
  EXPECT_TRUE(c.all[0].holds(num(198.5)));
  EXPECT_TRUE(c.all[0].holds(num(201.5)));
  EXPECT_FALSE(c.all[0].holds(num(201.6)));
  Reading nan;
  nan.valid = false;
  EXPECT_FALSE(c.all[0].holds(nan));  // a broken line equals nothing
  EXPECT_EQ(parse_condition("temperature.t >= 50C").all[0].value, 50);
}

TEST(ScenarioCondition, AxisStateByWord) {
  const Condition c = parse_condition("axis.slide.state == moving");
  Reading r;
  r.word = "moving";
  EXPECT_TRUE(c.all[0].holds(r));
  r.word = "idle";
  EXPECT_FALSE(c.all[0].holds(r));
  EXPECT_TRUE(parse_condition("axis.slide.state != moving").all[0].holds(r));
}

TEST(ScenarioCondition, ErrorsSayWhy) {
  struct Bad {
    const char* text;
    const char* why;
  } bad[] = {
      {"", "empty condition"},
      {"R0 =< 3", "expected ==, !=, <, <=, > or >="},
      {"R0 == x3", "'x3' is not a number"},
      {"R0 ==", "no value after =="},
      {"R0 == 1 or Y0", "'or' is not supported"},
      {"R0 == 1 Y0", "unexpected 'Y0'"},
      {"R0 < 3 +- 1", "a tolerance (+-) goes with == or != only"},
      {"axis.slide.state == running", "idle, moving or error"},
      {"axis.slide.speed > 3", ".position, .state or .frequency"},
      {"axes.slide > 1", "unknown kind 'axes.'"},
      {"R1:oct == 1", "unknown format 'oct'"},
      {"and Y0", "'and' needs a comparison on each side"},
      {"not R0 == 1", "'not' takes a name alone"},
  };
  for (const auto& b : bad) {
    try {
      parse_condition(b.text);
      ADD_FAILURE() << b.text << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(b.why), std::string::npos) << b.text << ": " << e.what();
    }
  }
}
