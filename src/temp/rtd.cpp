#include "plc_cell/temp/rtd.h"

#include <cmath>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace temp {

RtdCurve rtd_curve(double r0_ohm, const std::string& alpha) {
  if (alpha == "DIN" || alpha == "IEC" || alpha == "0.00385") return {r0_ohm, 3.9083e-3, -5.775e-7, -4.183e-12};
  if (alpha == "JIS" || alpha == "0.003916") return {r0_ohm, 3.9739e-3, -5.870e-7, -4.4e-12};
  throw Error("unknown RTD alpha '" + alpha + "' (DIN or JIS)");
}

double rtd_resistance(const RtdCurve& k, double t) {
  double f = 1 + k.a * t + k.b * t * t;
  if (t < 0) f += k.c * (t - 100) * t * t * t;
  return k.r0 * f;
}

double rtd_temperature(const RtdCurve& k, double r) {
  const double q = r / k.r0;
  // Root of B t^2 + A t + (1 - q) = 0, exact for t >= 0 and a close start below.
  double t = (-k.a + std::sqrt(k.a * k.a - 4 * k.b * (1 - q))) / (2 * k.b);
  if (q >= 1) return t;
  for (int i = 0; i < 20; ++i) {
    const double f = rtd_resistance(k, t) / k.r0 - q;
    const double d = k.a + 2 * k.b * t + k.c * (4 * t * t * t - 300 * t * t);
    const double step = f / d;
    t -= step;
    if (std::fabs(step) < 1e-9) break;
  }
  return t;
}

}  // namespace temp
}  // namespace plc_cell
