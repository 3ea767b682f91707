#pragma once
// NTC thermistors: the beta model and the Steinhart-Hart equation.
//   beta:           R = R25 exp(beta (1/T - 1/T25))
//   Steinhart-Hart: 1/T = a + b ln R + c (ln R)^3     (T in kelvin)
namespace plc_cell {
namespace temp {

constexpr double kKelvin = 273.15;

struct NtcBeta {
  double r25;   // ohm at 25 degC (the FBs-6NTC takes 2k, 5k, 10k or 20k)
  double beta;  // K
};
double ntc_resistance(const NtcBeta& n, double t_c);
double ntc_temperature(const NtcBeta& n, double r_ohm);

struct SteinhartHart {
  double a, b, c;
};
double ntc_resistance(const SteinhartHart& s, double t_c);  // solves the cubic in ln R
double ntc_temperature(const SteinhartHart& s, double r_ohm);
// The coefficients through three (degC, ohm) points.
SteinhartHart steinhart_hart_fit(double t1, double r1, double t2, double r2, double t3, double r3);

}  // namespace temp
}  // namespace plc_cell
