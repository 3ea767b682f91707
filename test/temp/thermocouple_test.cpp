// Thermocouple conversions against NIST ITS-90 table values (mV, rounded to 1 uV).
#include <gtest/gtest.h>

#include <cmath>

#include "plc_cell/temp/thermocouple.h"

namespace plc_cell {
namespace temp {
namespace {

struct Point {
  TcType type;
  double t_c;
  double emf_mv;
};

// From NIST Monograph 175 tables (and the range ends printed in allcoeff.tab).
const Point kNist[] = {
    {TcType::J, -210, -8.095}, {TcType::J, 100, 5.269},   {TcType::J, 500, 27.393},
    {TcType::J, 760, 42.919},  {TcType::J, 1200, 69.553}, {TcType::K, -200, -5.891},
    {TcType::K, 100, 4.096},   {TcType::K, 500, 20.644},  {TcType::K, 1000, 41.276},
    {TcType::K, 1372, 54.886}, {TcType::E, -200, -8.825}, {TcType::E, 100, 6.319},
    {TcType::E, 500, 37.005},  {TcType::E, 1000, 76.373}, {TcType::T, -200, -5.603},
    {TcType::T, 100, 4.279},   {TcType::T, 400, 20.872},  {TcType::R, -50, -0.226},
    {TcType::R, 100, 0.647},   {TcType::R, 250, 1.923},   {TcType::R, 1000, 10.506},
    {TcType::R, 1200, 13.228}, {TcType::R, 1768.1, 21.103}, {TcType::S, -50, -0.235},
    {TcType::S, 100, 0.646},   {TcType::S, 250, 1.874},   {TcType::S, 1000, 9.587},
    {TcType::S, 1200, 11.950}, {TcType::S, 1768.1, 18.693}, {TcType::B, 250, 0.291},
    {TcType::B, 700, 2.431},   {TcType::B, 1000, 4.834},  {TcType::B, 1820, 13.820},
    {TcType::N, -200, -3.990}, {TcType::N, 100, 2.774},   {TcType::N, 600, 20.613},
    {TcType::N, 1000, 36.256}, {TcType::N, 1300, 47.513},
};

TEST(Thermocouple, EmfMatchesNistTables) {
  for (const auto& p : kNist)
    EXPECT_NEAR(tc_emf_mv(p.type, p.t_c), p.emf_mv, 0.0006) << to_string(p.type) << " at " << p.t_c;
}

TEST(Thermocouple, InverseOfNistTableValues) {
  // The table EMF is rounded to 1 uV: allow that, divided by the sensitivity, plus the
  // NIST inverse's own error (<= 0.06 degC).
  for (const auto& p : kNist) {
    if (p.type == TcType::B && p.t_c < 300) continue;  // the B inverse starts at 250 degC and 0.291 mV
    const double s = (tc_emf_mv(p.type, p.t_c + 0.5) - tc_emf_mv(p.type, p.t_c - 0.5));
    const double tol = 0.06 + 0.0005 / s;
    EXPECT_NEAR(tc_temp_c(p.type, p.emf_mv), p.t_c, tol) << to_string(p.type) << " at " << p.t_c;
  }
}

// The FBs-TC module ranges (manual A:6760): the inverse must round-trip within 0.1 degC,
// the module's resolution, everywhere in them. The manual's R range ends at 1800 degC, past
// NIST's 1768.1 degC; that last part is extrapolated and not checked here.
TEST(Thermocouple, RoundTripWithinResolutionOverModuleRanges) {
  const struct { TcType t; double lo, hi; } ranges[] = {
      {TcType::J, -200, 900}, {TcType::K, -190, 1300}, {TcType::R, 0, 1768}, {TcType::S, 0, 1700},
      {TcType::E, -190, 1000}, {TcType::T, -190, 380}, {TcType::B, 350, 1800}, {TcType::N, -200, 1000}};
  for (const auto& r : ranges) {
    double worst = 0;
    for (double t = r.lo; t <= r.hi; t += 0.5)
      worst = std::max(worst, std::fabs(tc_temp_c(r.t, tc_emf_mv(r.t, t)) - t));
    EXPECT_LT(worst, 0.07) << to_string(r.t);
  }
}

TEST(Thermocouple, ColdJunctionCompensation) {
  // K at 200 degC hot, 30 degC terminals: the terminals see E(200) - E(30).
  const double e = tc_measured_emf_mv(TcType::K, 200, 30);
  EXPECT_NEAR(e, 8.138 - 1.203, 0.002);
  EXPECT_NEAR(tc_compensated_c(TcType::K, e, 30), 200.0, 0.06);
  // Without compensation the reading would be about 30 degC low.
  EXPECT_NEAR(tc_temp_c(TcType::K, e), 169.9, 0.1);
  for (TcType t : {TcType::J, TcType::E, TcType::T, TcType::N, TcType::R, TcType::S})
    EXPECT_NEAR(tc_compensated_c(t, tc_measured_emf_mv(t, 350, 22.5), 22.5), 350, 0.07) << to_string(t);
}

TEST(Thermocouple, TypeNames) {
  EXPECT_EQ(tc_type_from_string("k"), TcType::K);
  EXPECT_STREQ(to_string(TcType::N), "N");
  EXPECT_ANY_THROW(tc_type_from_string("X"));
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
