#include "plc_cell/scenario/raw_value.h"

#include <cmath>
#include <cstring>

#include "plc_cell/core/error.h"
#include "plc_cell/scenario/probe.h"

namespace plc_cell {
namespace scenario {

uint32_t raw_value(const Address& a, ValueFormat f, const Value& v, const std::string& text) {
  const int bits = value_bits(a);
  if (f == ValueFormat::F32) {
    const float x = float(v.number);
    uint32_t r;
    std::memcpy(&r, &x, sizeof r);
    return r;
  }
  if (v.number != std::floor(v.number)) throw Error(text + ": " + v.text + " is not a whole number");
  const double lo = bits == 1 ? 0 : -std::ldexp(1.0, bits - 1), hi = std::ldexp(1.0, bits) - 1;
  if (v.number < lo || v.number > hi)
    throw Error(text + ": value " + v.text + " out of range " + probe_number_text(lo) + ".." + probe_number_text(hi));
  const int64_t n = int64_t(v.number);
  return uint32_t(n < 0 ? n & (bits == 16 ? 0xFFFF : 0xFFFFFFFFLL) : n);
}

}  // namespace scenario
}  // namespace plc_cell
