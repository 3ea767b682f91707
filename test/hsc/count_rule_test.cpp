// Each counting mode against hand-made transitions (manual §10.2).
#include <gtest/gtest.h>

#include "plc_cell/hsc/count_rule.h"
#include "plc_cell/hsc/pulse_source.h"

namespace plc_cell {
namespace hsc {
namespace {

Pins P(bool a, bool b) { return Pins{a, b}; }

TEST(CountRule, UpDownCountsRisingEdgesAndSimultaneousEdgesCancel) {
  EXPECT_EQ(count_delta(Mode::UD, P(0, 0), P(1, 0)), 1);
  EXPECT_EQ(count_delta(Mode::UD, P(1, 0), P(0, 0)), 0);
  EXPECT_EQ(count_delta(Mode::UD, P(0, 0), P(0, 1)), -1);
  EXPECT_EQ(count_delta(Mode::UD, P(0, 0), P(1, 1)), 0);  // U and D rise together
  EXPECT_EQ(count_delta(Mode::UDx2, P(1, 0), P(0, 0)), 1);
  EXPECT_EQ(count_delta(Mode::UDx2, P(0, 1), P(0, 0)), -1);
  EXPECT_EQ(count_delta(Mode::UDx2, P(1, 1), P(0, 0)), 0);
}

TEST(CountRule, PulseDirection) {
  EXPECT_EQ(count_delta(Mode::PR, P(0, 0), P(1, 0)), 1);
  EXPECT_EQ(count_delta(Mode::PR, P(0, 1), P(1, 1)), -1);
  EXPECT_EQ(count_delta(Mode::PR, P(1, 0), P(0, 0)), 0);
  EXPECT_EQ(count_delta(Mode::PR, P(0, 0), P(0, 1)), 0);  // R alone never counts
  EXPECT_EQ(count_delta(Mode::PRx2, P(1, 1), P(0, 1)), -1);
  EXPECT_EQ(count_delta(Mode::PRx2, P(0, 0), P(1, 0)), 1);
}

// One full forward cycle (A leads B) then the same cycle backwards.
int run(Mode m, const std::vector<Pins>& seq) {
  int cv = 0;
  for (size_t i = 1; i < seq.size(); ++i) cv += count_delta(m, seq[i - 1], seq[i]);
  return cv;
}

TEST(CountRule, QuadratureMultipliersAndReversal) {
  const std::vector<Pins> fwd = {P(0, 0), P(1, 0), P(1, 1), P(0, 1), P(0, 0)};
  const std::vector<Pins> back = {P(0, 0), P(0, 1), P(1, 1), P(1, 0), P(0, 0)};
  EXPECT_EQ(run(Mode::AB, fwd), 1);
  EXPECT_EQ(run(Mode::ABx2, fwd), 2);
  EXPECT_EQ(run(Mode::ABx3, fwd), 3);
  EXPECT_EQ(run(Mode::ABx4, fwd), 4);
  EXPECT_EQ(run(Mode::AB, back), -1);
  EXPECT_EQ(run(Mode::ABx2, back), -2);
  EXPECT_EQ(run(Mode::ABx3, back), -3);
  EXPECT_EQ(run(Mode::ABx4, back), -4);
  // Reversal in mid-cycle: two steps forward, two back: net zero in every mode.
  const std::vector<Pins> wobble = {P(0, 0), P(1, 0), P(1, 1), P(1, 0), P(0, 0)};
  for (Mode m : {Mode::AB, Mode::ABx2, Mode::ABx3, Mode::ABx4}) EXPECT_EQ(run(m, wobble), 0);
  // MD4: +1 exactly at A rising while B = 0; the same edge backwards is -1 at A falling.
  EXPECT_EQ(count_delta(Mode::AB, P(0, 0), P(1, 0)), 1);
  EXPECT_EQ(count_delta(Mode::AB, P(1, 0), P(0, 0)), -1);
  EXPECT_EQ(count_delta(Mode::AB, P(1, 1), P(0, 1)), 0);
  // Both phases at once is illegal: no count.
  EXPECT_EQ(count_delta(Mode::ABx4, P(0, 0), P(1, 1)), 0);
}

TEST(PulseSource, ExactQuartersAndCrossingTimes) {
  PulseSource s("enc", 0, 1);
  s.set_rate(0, 460000.0);  // 460 kHz per phase: 1.84 M quarters/s
  EXPECT_EQ(s.quarter(1000000000ull), 1840000);
  EXPECT_EQ(s.quarter(1000000000ull - 1), 1839999);
  const uint64_t t = s.time_of_quarter(1840000, 0);
  EXPECT_EQ(t, 1000000000ull);
  s.set_rate(1000000000ull, -460000.0);  // reverse at 1 s
  EXPECT_EQ(s.quarter(2000000000ull), 0);
  EXPECT_EQ(s.time_of_quarter(-1, 1000000000ull) > 2000000000ull, true);
  PulseSource p("slow", 4, -1);
  p.set_rate(0, 3.0);  // 3 Hz: a third of a second is not a whole number of ns
  EXPECT_EQ(p.quarter(333333333), 3);
  EXPECT_EQ(p.quarter(333333334), 4);
  EXPECT_EQ(p.time_of_quarter(4, 0), 333333334u);
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
