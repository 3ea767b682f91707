#pragma once
// Properties of a scenario file: conditions that hold at every scan of every case
// ("never: Y0 and Y1", "always: X5 -> not Y3"), in the condition language of condition.h.
#include <string>

#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace scenario {

// The text after "never:" or "always:". "A -> B" is an implication (always only); throws
// plc_cell::Error saying what is wrong.
Property parse_property(bool never, const std::string& text, Naming naming = Naming::Cell);

// A property's state over the scans of one case: when its violation began, so that a
// grace time (within) can pass before it counts.
class PropertyWatch {
 public:
  explicit PropertyWatch(const Property& p) : p_(&p) {}
  // After the scan at now_us: true when the violation has lasted longer than its grace, or
  // than min_grace_us if that is longer (the spread of the values read: Target::spread_us).
  bool failed(bool violated_now, uint64_t now_us, uint64_t min_grace_us = 0);
  uint64_t since_us() const { return since_us_; }
  const Property& property() const { return *p_; }

 private:
  const Property* p_;
  bool violated_ = false;
  uint64_t since_us_ = 0;
};

}  // namespace scenario
}  // namespace plc_cell
