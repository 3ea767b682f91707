// The wire's model alone (delay_line.h): which edges a sample brings and at what instant.
#include <gtest/gtest.h>

#include "plc_cell/line/delay_line.h"

namespace plc_cell {
namespace line {
namespace {

std::vector<WireEdge> samples(DelayLine& d, const std::vector<std::pair<uint64_t, uint32_t>>& s) {
  std::vector<WireEdge> out;
  for (const auto& x : s) d.sample(x.first, x.second, &out);
  return out;
}

::testing::AssertionResult edges_are(const std::vector<WireEdge>& got, const std::vector<WireEdge>& want) {
  std::string g, w;
  for (const auto& e : got) g += "(" + std::to_string(e.t_ns) + "," + std::to_string(e.value) + ")";
  for (const auto& e : want) w += "(" + std::to_string(e.t_ns) + "," + std::to_string(e.value) + ")";
  if (g == w) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "got " << g << ", want " << w;
}

TEST(DelayLine, AChangeArrivesAfterTheDelayAndOnlyChangesTravel) {
  WireModel m;
  m.delay_ns = 2000000;  // 2 ms
  DelayLine d(m, 0);
  EXPECT_EQ(d.initial(), 0u);
  // 5 ms ON, 6 ms ON again (no change), 9 ms OFF.
  EXPECT_TRUE(edges_are(samples(d, {{5000, 1}, {6000, 1}, {9000, 0}}), {{7000000, 1}, {11000000, 0}}));
}

TEST(DelayLine, AZeroDelayArrivesOneNanosecondAfterTheScan) {
  DelayLine d(WireModel{}, 0);
  EXPECT_TRUE(edges_are(samples(d, {{5000, 1}}), {{5000001, 1}}));
}

TEST(DelayLine, AnInvertedWireStartsOnAndInvertsEveryEdge) {
  WireModel m;
  m.invert = true;
  DelayLine d(m, 0);
  EXPECT_EQ(d.initial(), 1u);
  EXPECT_TRUE(edges_are(samples(d, {{1000, 1}, {2000, 0}}), {{1000001, 0}, {2000001, 1}}));
}

TEST(DelayLine, ARegisterTravelsWhole) {
  WireModel m;
  m.delay_ns = 1000;
  DelayLine d(m, 7);
  EXPECT_EQ(d.initial(), 7u);
  EXPECT_TRUE(edges_are(samples(d, {{0, 7}, {1000, 65535}, {2000, 3}}), {{1001000, 65535}, {2001000, 3}}));
}

TEST(DelayLine, EachRisingEdgeIsAPartAndOverlappingPartsMerge) {
  WireModel m;
  m.part = true;
  m.travel_ns = 10000000;  // 10 ms
  m.length_ns = 3000000;   // 3 ms
  DelayLine d(m, 0);
  EXPECT_EQ(d.initial(), 0u);
  // Rising at 0, 2 and 20 ms (falling in between): parts over [10, 13), [12, 15), [30, 33)
  // ms. The second arrives while the first covers the sensor: the edge that uncovers it at
  // 13 ms is followed at 13 ms by one that covers it again, until 15 ms.
  EXPECT_TRUE(edges_are(samples(d, {{0, 1}, {1000, 0}, {2000, 1}, {3000, 0}, {20000, 1}, {21000, 0}}),
                        {{10000000, 1}, {13000000, 0}, {13000000, 1}, {15000000, 0}, {30000000, 1}, {33000000, 0}}));
}

TEST(DelayLine, APartThatArrivesAsTheLastLeavesKeepsTheSensorCovered) {
  WireModel m;
  m.part = true;
  m.travel_ns = 5000000;
  m.length_ns = 2000000;
  DelayLine d(m, 0);
  // Parts at 0 and 2 ms: [5, 7) and [7, 9): the sensor stays covered from 5 to 9 ms.
  EXPECT_TRUE(edges_are(samples(d, {{0, 1}, {1000, 0}, {2000, 1}}), {{5000000, 1}, {7000000, 0}, {7000000, 1}, {9000000, 0}}));
}

TEST(DelayLine, AnInvertedPartUncoversTheSensor) {
  WireModel m;
  m.part = true;
  m.invert = true;
  m.travel_ns = 1000;
  m.length_ns = 1000;
  DelayLine d(m, 0);
  EXPECT_EQ(d.initial(), 1u);  // a dark-on sensor: ON while no part is there
  EXPECT_TRUE(edges_are(samples(d, {{0, 1}}), {{1000, 0}, {2000, 1}}));
}

}  // namespace
}  // namespace line
}  // namespace plc_cell
