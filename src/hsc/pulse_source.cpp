#include "plc_cell/hsc/pulse_source.h"

#include <cmath>

namespace plc_cell {
namespace hsc {

namespace {
constexpr int64_t kPicoPerQuarter = 250000000000;  // 1e12 / 4

__int128 floor_div(__int128 a, __int128 b) {
  __int128 q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}
__int128 ceil_div(__int128 a, __int128 b) { return -floor_div(-a, b); }
}  // namespace

void PulseSource::set_rate(uint64_t t_ns, double hz) {
  if (t_ns > t0_) p0_ += __int128(t_ns - t0_) * rate_mhz_;
  t0_ = t_ns;
  rate_mhz_ = static_cast<int64_t>(std::llround(hz * 1000.0));
}

int64_t PulseSource::quarter(uint64_t t_ns) const {
  const __int128 p = p0_ + (t_ns > t0_ ? __int128(t_ns - t0_) * rate_mhz_ : 0);
  return static_cast<int64_t>(floor_div(p, kPicoPerQuarter));
}

uint64_t PulseSource::time_of_quarter(int64_t q, uint64_t from_ns) const {
  if (rate_mhz_ == 0) return UINT64_MAX;
  __int128 d;  // ns after t0_
  if (rate_mhz_ > 0) {
    d = ceil_div(__int128(q) * kPicoPerQuarter - p0_, rate_mhz_);  // p >= q quarters
  } else {
    d = ceil_div(p0_ - (__int128(q + 1) * kPicoPerQuarter - 1), -__int128(rate_mhz_));  // p < q+1 quarters
  }
  if (d < 0) d = 0;
  const __int128 t = __int128(t0_) + d;
  if (t > __int128(UINT64_MAX / 2)) return UINT64_MAX;
  return t < __int128(from_ns) ? from_ns : static_cast<uint64_t>(t);
}

}  // namespace hsc
}  // namespace plc_cell
