// R4056 = 5AH: the output frequency follows the SPD register during the output.
#include <cmath>

#include "motion_fixture.h"

namespace plc_cell {
namespace motion {
namespace {

constexpr double kA = 4.6e6, kF0 = 141;

TEST(DynamicSpeed, With5AhTheRestOfTheMoveRunsAtTheNewSpeed) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD D10\nDRV ADR,+,50000,Ps\nGOTO NEXT\nMEND\n");
  c.put("R4056", 0x5A);
  c.put("DD10", 10000);
  c.put("M1", 1);
  c.run(1000000);  // scans 0 .. 999 ms
  c.put("DD10", 20000);
  c.run(2000);  // the 1 s scan sees it; 1 ms later the ramp is under way
  EXPECT_EQ(c.get32("DR4080"), 10000 + 4600);
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 1; }, 10000000));
  EXPECT_EQ(c.get32("DR4088"), 50000);
  // Closed form: at 1 s, s1 pulses at 10 kHz; then 10 -> 20 kHz, cruise, 20 kHz -> P5.
  const double ta = (10000 - kF0) / kA, sa = (1e8 - kF0 * kF0) / (2 * kA);
  const double s1 = std::floor(sa + (1.0 - ta) * 10000);  // whole pulses sent by 1 s
  const double frac = sa + (1.0 - ta) * 10000 - s1;        // of the next pulse
  const double left = 50000 - s1 - frac;                   // continuous position left
  const double up = (4e8 - 1e8) / (2 * kA), down = (4e8 - kF0 * kF0) / (2 * kA);
  const double t_rest = (20000 - 10000) / kA + (left - up - down) / 20000 + (20000 - kF0) / kA;
  EXPECT_NEAR(c.done[0].t_ns * 1e-9, 1.0 + t_rest, 1e-4);  // within one pulse period at 10 kHz
}

TEST(DynamicSpeed, WithoutIt) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD D10\nDRV ADR,+,50000,Ps\nGOTO NEXT\nMEND\n");
  c.put("DD10", 10000);
  c.put("M1", 1);
  c.run(1000000);
  c.put("DD10", 20000);
  c.run(100000);
  EXPECT_EQ(c.get32("DR4080"), 10000);
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell
