#pragma once
// The pins of the axes configured with `output:` (Y2n, Y2n+1 show the pulse train) and
// what the cell YAML wires from them: `wiring:` (the pins looped back to inputs) and
// `encoder:` (an encoder on the load), as edge sources of the counters
// (docs/motion.md "Pulse pins").
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "plc_cell/motion/axis_config.h"
#include "plc_cell/motion/axis_state.h"
#include "plc_cell/motion/pulse_pins.h"

namespace plc_cell {

class Memory;
namespace hsc {
class HscUnit;
}

namespace motion {

class AxisWiring {
 public:
  AxisWiring(const AxesConfig& cfg, const AxisStates& axes, Memory& mem, hsc::HscUnit* counters)
      : cfg_(cfg), axes_(axes), mem_(mem), hsc_(counters) {}
  AxisWiring(const AxisWiring&) = delete;
  AxisWiring& operator=(const AxisWiring&) = delete;

  // Makes the configured signals and hands them to the counters (throws SourceError
  // naming the YAML line if they clash).
  void attach();
  void detach();
  // The Y image of the owned pins shows their level at t.
  void write_pins(uint64_t t) const {
    if (any_pins_) write_owned_pins(t);  // most cells have none: twice a scan, no call
  }
  const AxisSignal* pins(int ps) const { return pins_[ps]; }
  hsc::HscUnit* counters() const { return hsc_; }

 private:
  void write_owned_pins(uint64_t t) const;

  const AxesConfig& cfg_;
  const AxisStates& axes_;
  Memory& mem_;
  hsc::HscUnit* hsc_;  // the counters' unit (pins, encoders), if any
  std::vector<std::unique_ptr<AxisSignal>> signals_;  // owned; the counters hold pointers
  std::array<const AxisSignal*, kAxes> pins_{};
  bool any_pins_ = false;
};

}  // namespace motion
}  // namespace plc_cell
