#pragma once
// Platinum RTDs (Pt100, Pt1000) by Callendar-Van Dusen:
//   R(t) = R0 (1 + A t + B t^2)                 t >= 0 degC
//   R(t) = R0 (1 + A t + B t^2 + C (t-100) t^3) t <  0 degC
// DIN/IEC 60751 (alpha 0.00385) and JIS C1604-1981 (alpha 0.003916) coefficient sets.
#include <string>

namespace plc_cell {
namespace temp {

struct RtdCurve {
  double r0;  // ohm at 0 degC: 100 (Pt100) or 1000 (Pt1000)
  double a, b, c;
};

// alpha is "DIN" (0.00385, the default) or "JIS" (0.003916); throws Error otherwise.
RtdCurve rtd_curve(double r0_ohm, const std::string& alpha = "DIN");

double rtd_resistance(const RtdCurve& k, double t_c);
// Closed form above 0 degC, Newton iteration below (C makes it quartic).
double rtd_temperature(const RtdCurve& k, double r_ohm);

}  // namespace temp
}  // namespace plc_cell
