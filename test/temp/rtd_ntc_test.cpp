// RTD and NTC conversions against published reference values.
#include <gtest/gtest.h>

#include <cmath>

#include "plc_cell/temp/ntc.h"
#include "plc_cell/temp/rtd.h"

namespace plc_cell {
namespace temp {
namespace {

// IEC 60751 Pt100 table (ohm, 0.01 ohm printed).
TEST(Rtd, Pt100MatchesIec60751Table) {
  const RtdCurve pt = rtd_curve(100);
  const struct { double t, r; } table[] = {{-200, 18.52}, {-100, 60.26}, {-50, 80.31}, {0, 100.00},
                                           {100, 138.51}, {200, 175.86}, {400, 247.09}, {600, 313.71},
                                           {850, 390.48}};
  for (const auto& p : table) {
    EXPECT_NEAR(rtd_resistance(pt, p.t), p.r, 0.006) << p.t;
    // 0.005 ohm of table rounding is about 0.013 degC: well inside the 0.1 degC resolution.
    EXPECT_NEAR(rtd_temperature(pt, p.r), p.t, 0.05) << p.t;
  }
}

TEST(Rtd, Pt1000AndJisRoundTrip) {
  for (const char* alpha : {"DIN", "JIS"}) {
    const RtdCurve pt = rtd_curve(1000, alpha);
    for (double t = -200; t <= 850; t += 0.7)
      EXPECT_NEAR(rtd_temperature(pt, rtd_resistance(pt, t)), t, 1e-6) << alpha << " " << t;
  }
  EXPECT_NEAR(rtd_resistance(rtd_curve(1000), 100), 1385.055, 0.001);
  // JIS alpha = (R100 - R0) / (100 R0) = 0.003916.
  const RtdCurve jis = rtd_curve(100, "JIS");
  EXPECT_NEAR((rtd_resistance(jis, 100) - 100) / 100 / 100, 0.003916, 2e-6);
  EXPECT_ANY_THROW(rtd_curve(100, "XYZ"));
}

TEST(Ntc, BetaModel) {
  const NtcBeta n{10000, 3950};
  EXPECT_NEAR(ntc_resistance(n, 25), 10000, 1e-9);
  // 10k/3950: R(0) = 10k exp(3950 (1/273.15 - 1/298.15)) = 33.6 kohm; R(100) = 0.6975 kohm.
  EXPECT_NEAR(ntc_resistance(n, 0), 33621, 10);
  EXPECT_NEAR(ntc_resistance(n, 100), 697.5, 0.1);
  for (double t = -40; t <= 150; t += 0.3) EXPECT_NEAR(ntc_temperature(n, ntc_resistance(n, t)), t, 1e-9);
}

TEST(Ntc, SteinhartHartFitAndInverse) {
  // A 10 kohm thermistor's datasheet points (-10 degC 55.33k, 25 degC 10k, 85 degC 1.071k).
  const SteinhartHart s = steinhart_hart_fit(-10, 55330, 25, 10000, 85, 1071);
  EXPECT_NEAR(ntc_temperature(s, 55330), -10, 1e-6);
  EXPECT_NEAR(ntc_temperature(s, 10000), 25, 1e-6);
  EXPECT_NEAR(ntc_temperature(s, 1071), 85, 1e-6);
  for (double t = -40; t <= 150; t += 0.3) EXPECT_NEAR(ntc_temperature(s, ntc_resistance(s, t)), t, 1e-6);
  // Steinhart-Hart and beta agree near 25 degC for a 3950 K part within a few tenths.
  EXPECT_NEAR(ntc_temperature(s, ntc_resistance(NtcBeta{10000, 3950}, 50)), 50, 1.0);
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
