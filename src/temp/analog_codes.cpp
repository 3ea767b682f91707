#include "plc_cell/temp/analog_codes.h"

#include <algorithm>
#include <cmath>

namespace plc_cell {
namespace temp {

int32_t ai_code14(const AnalogRange& r, double x, bool bipolar_code) {
  const double lo = r.lo(), hi = r.hi();
  double u = (std::clamp(x, lo, hi) - lo) / (hi - lo) * 16383.0;
  // Round half up, so the bipolar mid-scale 8191.5 reads 8192 (manual A:5969).
  int32_t code = int32_t(std::floor(u + 0.5));
  code = std::clamp(code, 0, 16383);
  return bipolar_code ? code - 8192 : code;
}

int32_t ai_register(int32_t code14, AiFormat f) {
  switch (f) {
    case AiFormat::Valid14: return code14;
    case AiFormat::Valid12In14: return code14 & ~int32_t(3);  // two's complement keeps the sign
    case AiFormat::Bits12: return code14 >> 2;                 // arithmetic shift: -8192 -> -2048
  }
  return code14;
}

double ao_signal(const AnalogRange& r, int32_t code, bool bipolar_code) {
  const int32_t u = std::clamp(bipolar_code ? code + 8192 : code, 0, 16383);
  return r.lo() + double(u) * (r.hi() - r.lo()) / 16383.0;
}

int32_t offset_4_20(int32_t ir, bool bipolar_code) {
  const int32_t rn = ir + (bipolar_code ? 8192 : 0) - 3276;  // 3276 = 16383 x 4/20
  return std::min(16383, std::max(0, rn) * 20 / 16);
}

}  // namespace temp
}  // namespace plc_cell
