#pragma once
// The TRi FMD1616's ADC/DAC conditioning (its manual, sections 5.2.6 and 5.5) as a
// per-channel option of the simulated analog channels: a moving average over the last
// 1-9 samples (inputs only), a gain (1 + x/10000) and a zero offset of -100..+100
// counts. Counts are the channel's own converter counts; docs/analog-and-temperature.md.
#include <cstdint>
#include <string>

#include <yaml-cpp/yaml.h>

#include "plc_cell/config/yaml_reader.h"

namespace plc_cell {
namespace temp {

struct ConditioningDef {
  bool enabled = false;  // no `conditioning:` key: the channel behaves as without it
  int average = 1;       // samples, 1 = the latest one
  int gain = 0;          // x of (1 + x/10000)
  int offset = 0;        // counts added after the gain
};

constexpr int kMaxAverage = 9, kMaxOffset = 100, kMaxGain = 9999;

// The `conditioning:` mapping of a channel at key; output channels take no average.
ConditioningDef parse_conditioning(const YamlReader& r, const YAML::Node& n, const std::string& key, bool output);

// (sum / samples) x (1 + gain/10000) + offset, rounded half away from zero once, in
// exact integer arithmetic, then clamped to lo..hi.
int32_t condition_code(int64_t sum, int samples, int gain, int offset, int32_t lo, int32_t hi);

// One channel's FIFO of the last `average` samples; before it is full the mean is over
// the samples taken so far.
class ConditionedChannel {
 public:
  ConditionedChannel() = default;
  explicit ConditionedChannel(const ConditioningDef& d) : def_(d) {}
  bool enabled() const { return def_.enabled; }
  // Takes one sample and returns the conditioned code.
  int32_t sample(int32_t code, int32_t lo, int32_t hi);
  // A value written to an output: no history.
  int32_t output(int32_t code, int32_t lo, int32_t hi) const;

 private:
  ConditioningDef def_;
  int32_t fifo_[kMaxAverage] = {};
  int count_ = 0, next_ = 0;
};

}  // namespace temp
}  // namespace plc_cell
