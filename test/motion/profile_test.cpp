// Profiles against closed-form values: total pulses, peak, phase times, pulse instants.
#include <gtest/gtest.h>

#include <cmath>

#include "plc_cell/motion/profile.h"

namespace plc_cell {
namespace motion {
namespace {

// Defaults of FUN141: P4 = 460000 Hz, P8 = 5000 ms -> 92000 Hz/s; P5 = 141 Hz.
constexpr double kA = 92000, kF0 = 141;

TEST(Profile, LongMoveIsATrapezoidWithTheClosedFormPhases) {
  const double fv = 50000;
  const int64_t n = 100000;
  const Profile p = Profile::plan(n, kF0, fv, kF0, kA, kA);
  const double ta = (fv - kF0) / kA;             // accel time
  const double sa = (fv * fv - kF0 * kF0) / (2 * kA);  // accel pulses (= decel pulses)
  const double tc = (n - 2 * sa) / fv;           // cruise
  ASSERT_EQ(p.segments().size(), 3u);
  EXPECT_NEAR(p.segments()[1].t0, ta, 1e-12);
  EXPECT_NEAR(p.segments()[2].t0, ta + tc, 1e-9);
  EXPECT_NEAR(p.duration(), 2 * ta + tc, 1e-9);
  EXPECT_DOUBLE_EQ(p.peak(), fv);
  EXPECT_EQ(p.emitted(p.duration()), n);
  EXPECT_EQ(p.emitted(p.duration() - 1e-6), n - 1);  // pulse N is the end (last period 7 ms)
  // Pulse k at the closed-form instant: in the ramp k = f0 t + a t^2/2.
  for (int64_t k : {1, 10, 1000, 13000}) {
    const double t = (-kF0 + std::sqrt(kF0 * kF0 + 2 * kA * k)) / kA;
    EXPECT_NEAR(p.time_of(static_cast<double>(k)), t, 1e-9) << k;
    EXPECT_EQ(p.emitted(t + 1e-9), k);
    EXPECT_EQ(p.emitted(t - 1e-6), k - 1);
  }
  // In the cruise, pulses are exactly 1/fv apart.
  const double k0 = std::ceil(sa) + 10;
  EXPECT_NEAR(p.time_of(k0 + 1) - p.time_of(k0), 1 / fv, 1e-12);
}

TEST(Profile, ShortMoveIsATriangleWithTheClosedFormPeak) {
  const int64_t n = 2000;
  const double fv = 200000;
  const Profile p = Profile::plan(n, kF0, fv, kF0, kA, kA);
  const double vp = std::sqrt(kF0 * kF0 + n * kA);  // vp^2 = f0^2 + 2 N a d / (a + d), a = d
  EXPECT_NEAR(p.peak(), vp, 1e-6);
  EXPECT_LT(p.peak(), fv);
  EXPECT_NEAR(p.duration(), 2 * (vp - kF0) / kA, 1e-9);
  EXPECT_EQ(p.emitted(p.duration()), n);
  EXPECT_NEAR(p.velocity(p.duration() / 2), vp, 1e-3);
}

TEST(Profile, SeparateDecelerationMakesAnAsymmetricTriangle) {
  const double a = 92000, d = 4 * 92000;  // P12 = P8 / 4
  const int64_t n = 5000;
  const Profile p = Profile::plan(n, kF0, 400000, kF0, a, d);
  const double vp = std::sqrt((2 * n * a * d + d * kF0 * kF0 + a * kF0 * kF0) / (a + d));
  EXPECT_NEAR(p.peak(), vp, 1e-6);
  EXPECT_NEAR(p.duration(), (vp - kF0) / a + (vp - kF0) / d, 1e-9);
  EXPECT_EQ(p.emitted(p.duration()), n);
}

TEST(Profile, SpeedBelowTheStartSpeedRunsConstant) {
  const Profile p = Profile::plan(100, 100, 100, kF0, kA, kA);  // the axis starts at min(P5, SPD);
  EXPECT_NEAR(p.duration(), 1.0, 1e-12);
  EXPECT_EQ(p.emitted(0.5 + 1e-9), 50);
}

TEST(Profile, NoAccelerationTimeIsASquareProfile) {
  const Profile p = Profile::plan(5000, kF0, 5000, kF0, kInf, kInf);
  EXPECT_NEAR(p.duration(), 1.0, 1e-12);
  EXPECT_EQ(p.emitted(1.0), 5000);
}

TEST(Profile, EndlessCruisesForever) {
  const Profile p = Profile::plan(-1, kF0, 10000, kF0, kA, kA);
  EXPECT_TRUE(p.endless());
  const double ta = (10000 - kF0) / kA;
  const double sa = (10000.0 * 10000 - kF0 * kF0) / (2 * kA);
  EXPECT_NEAR(p.position(ta + 100), sa + 100 * 10000, 1e-3);
}

TEST(Profile, DecelerationStopEndsOnAWholePulseAtTheStopSpeed) {
  const double v = 50000;
  const Profile p = Profile::stop(v, kF0, kA, -1);
  const double d = (v * v - kF0 * kF0) / (2 * kA);
  EXPECT_EQ(p.pulses(), static_cast<int64_t>(std::ceil(d)));
  EXPECT_NEAR(p.velocity((v - kF0) / kA - 1e-9), kF0, 1e-3);
  EXPECT_EQ(p.emitted(p.duration()), p.pulses());
  EXPECT_EQ(Profile::stop(v, kF0, kA, 10).pulses(), 10);  // never past the move's end
}

TEST(Profile, DrvcSectionAcceleratesWithoutStopping) {
  const Profile p = Profile::plan(20000, kF0, 10000, 10000, kA, kA);
  EXPECT_DOUBLE_EQ(p.end_speed(), 10000);
  EXPECT_NEAR(p.velocity(p.duration() - 1e-9), 10000, 1e-3);
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell
