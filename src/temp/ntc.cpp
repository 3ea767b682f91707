#include "plc_cell/temp/ntc.h"

#include <cmath>

namespace plc_cell {
namespace temp {

double ntc_resistance(const NtcBeta& n, double t_c) {
  return n.r25 * std::exp(n.beta * (1 / (t_c + kKelvin) - 1 / (25 + kKelvin)));
}

double ntc_temperature(const NtcBeta& n, double r) {
  return 1 / (1 / (25 + kKelvin) + std::log(r / n.r25) / n.beta) - kKelvin;
}

double ntc_temperature(const SteinhartHart& s, double r) {
  const double l = std::log(r);
  return 1 / (s.a + s.b * l + s.c * l * l * l) - kKelvin;
}

double ntc_resistance(const SteinhartHart& s, double t_c) {
  // c x^3 + b x + (a - 1/T) = 0 has one real root (Cardano), x = ln R.
  const double y = (s.a - 1 / (t_c + kKelvin)) / s.c;
  const double p = s.b / (3 * s.c);
  const double d = std::sqrt(p * p * p + y * y / 4);
  return std::exp(std::cbrt(d - y / 2) - std::cbrt(d + y / 2));
}

SteinhartHart steinhart_hart_fit(double t1, double r1, double t2, double r2, double t3, double r3) {
  const double l1 = std::log(r1), l2 = std::log(r2), l3 = std::log(r3);
  const double y1 = 1 / (t1 + kKelvin), y2 = 1 / (t2 + kKelvin), y3 = 1 / (t3 + kKelvin);
  const double g2 = (y2 - y1) / (l2 - l1), g3 = (y3 - y1) / (l3 - l1);
  const double c = (g3 - g2) / (l3 - l2) / (l1 + l2 + l3);
  const double b = g2 - c * (l1 * l1 + l1 * l2 + l2 * l2);
  const double a = y1 - (b + l1 * l1 * c) * l1;
  return {a, b, c};
}

}  // namespace temp
}  // namespace plc_cell
