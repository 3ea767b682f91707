#include "plc_cell/temp/analog_conditioning.h"

#include <algorithm>
#include <set>

namespace plc_cell {
namespace temp {
namespace {

// A whole number in lo..hi, else an error that says what the field is for.
int whole(const YamlReader& r, const YAML::Node& n, const std::string& key, int lo, int hi, const std::string& what) {
  int64_t v = 0;
  bool ok = n.IsScalar();
  if (ok) {
    try {
      v = n.as<int64_t>();
    } catch (const YAML::Exception&) {
      ok = false;
    }
  }
  const std::string got = n.IsScalar() ? n.as<std::string>() : std::string("a non-scalar");
  if (!ok) r.fail(n, key, what + ": a whole number " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " + got);
  if (v < lo || v > hi)
    r.fail(n, key, what + ": " + got + " out of range " + std::to_string(lo) + ".." + std::to_string(hi));
  return int(v);
}

}  // namespace

ConditioningDef parse_conditioning(const YamlReader& r, const YAML::Node& n, const std::string& key, bool output) {
  ConditioningDef d;
  if (!n.IsMap()) r.fail(n, key, output ? "expected a mapping {gain, offset}" : "expected a mapping {average, gain, offset}");
  if (output && n["average"])
    r.fail(n["average"], key + ".average", "an output has no moving average (the TRi averages ADC readings only)");
  r.only(n, key, output ? std::set<std::string>{"gain", "offset"} : std::set<std::string>{"average", "gain", "offset"});
  d.enabled = true;
  if (n["average"]) d.average = whole(r, n["average"], key + ".average", 1, kMaxAverage, "moving average samples");
  // The TRi's field is +-0.xxxx, so x is 4 digits and the factor stays in 0.0001..1.9999.
  if (n["gain"]) d.gain = whole(r, n["gain"], key + ".gain", -kMaxGain, kMaxGain, "gain x of (1 + x/10000)");
  if (n["offset"]) d.offset = whole(r, n["offset"], key + ".offset", -kMaxOffset, kMaxOffset, "zero offset in counts");
  return d;
}

int32_t condition_code(int64_t sum, int samples, int gain, int offset, int32_t lo, int32_t hi) {
  const int64_t den = int64_t(samples) * 10000;
  const int64_t num = sum * (10000 + gain) + int64_t(offset) * den;
  // Half away from zero, on the exact fraction: no binary rounding of x/10000.
  const int64_t q = num >= 0 ? (2 * num + den) / (2 * den) : -((-2 * num + den) / (2 * den));
  return int32_t(std::clamp<int64_t>(q, lo, hi));
}

int32_t ConditionedChannel::sample(int32_t code, int32_t lo, int32_t hi) {
  fifo_[next_] = code;  // the newest sample overwrites the oldest
  next_ = (next_ + 1) % def_.average;
  count_ = std::min(count_ + 1, def_.average);
  int64_t sum = 0;
  for (int i = 0; i < count_; ++i) sum += fifo_[i];
  return condition_code(sum, count_, def_.gain, def_.offset, lo, hi);
}

int32_t ConditionedChannel::output(int32_t code, int32_t lo, int32_t hi) const {
  return condition_code(code, 1, def_.gain, def_.offset, lo, hi);
}

}  // namespace temp
}  // namespace plc_cell
