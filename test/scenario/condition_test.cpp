// Conditions as docs/testing-your-cell.md defines them ("What a condition reads").
#include <gtest/gtest.h>

#include <map>

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

// Sums (docs/testing-your-cell.md, "Sums"): names and numbers on either side, the right
// side's names subtracted, its numbers the value compared with.
TEST(ScenarioCondition, SumsOfNamesOnEitherSide) {
  const Condition c = parse_condition("R0 + R1 - 2 == R2 + 5 and M0");
  ASSERT_EQ(c.all.size(), 2u);
  const Comparison& s = c.all[0];
  EXPECT_EQ(s.probe.name, "R0");
  ASSERT_EQ(s.more.size(), 2u);
  EXPECT_EQ(s.more[0].sign, 1);
  EXPECT_EQ(s.more[0].probe.name, "R1");
  EXPECT_EQ(s.more[1].sign, -1);
  EXPECT_EQ(s.more[1].probe.name, "R2");
  EXPECT_EQ(s.value, 7);  // R0 + R1 - R2 == 5 + 2
  std::map<std::string, double> v = {{"R0", 10}, {"R1", 4}, {"R2", 7}};
  const auto read = [&](const Probe& p) { return num(v[p.name]); };
  EXPECT_TRUE(s.holds(read));  // 10 + 4 - 2 == 7 + 5
  v["R2"] = 8;
  EXPECT_FALSE(s.holds(read));
  const Condition t = parse_condition("R0 + R1 == 3 +- 0.5");
  EXPECT_EQ(t.all[0].tolerance, 0.5);
  v = {{"R0", 1}, {"R1", 2.4}};
  EXPECT_TRUE(t.all[0].holds(read));
  v["R1"] = 2.6;
  EXPECT_FALSE(t.all[0].holds(read));
  // A line's names sum across its cells.
  const Condition l = parse_condition("infeed.R0 == test.R1 + test.R3", Naming::Line);
  EXPECT_EQ(l.all[0].probe.cell, "infeed");
  EXPECT_EQ(l.all[0].more[1].probe.cell, "test");
  EXPECT_EQ(l.all[0].more[1].sign, -1);
}

TEST(ScenarioCondition, ASumsErrorsSayWhy) {
  auto why = [](const std::string& text) {
    try {
      parse_condition(text);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(why("R0 + R1"), "'R0 + R1': a sum is compared: A + B == C (==, !=, <, <=, > or >=)");
  EXPECT_EQ(why("R0 + == R1"), "'R0 + == R1': a term is missing at the end of a side");
  EXPECT_EQ(why("R0 + R1 + == 3"), "'R0 + R1 + == 3': a term is missing at the end of a side");
  EXPECT_EQ(why("- R0 == R1"), "'- R0 == R1': a term is missing before '-'");
  EXPECT_EQ(why("3 - R0 == R1"), "'3 - R0 == R1': a sum starts with a name (A + B == C)");
  EXPECT_EQ(why("3 == R0 + R1"), "'3 == R0 + R1': a sum starts with a name (A + B == C)");
  EXPECT_EQ(why("R0 R1 + 2 == 3"), "'R0 R1 + 2 == 3': expected + or - between terms, got 'R1'");
  EXPECT_EQ(why("R0 + R1 > 3 +- 1"), "'R0 + R1 > 3 +- 1': a tolerance (+-) goes with == or != only");
  EXPECT_EQ(why("axis.x.state + R0 == 1"), "'axis.x.state + R0 == 1': an axis state is a word: it is not summed");
}
