#pragma once
// The step-speed component: the speeds and rates of each axis's FUN140 moves, from
// FUN141's time-based ramp (P4, P5, P8, P12) or from the cell YAML's `stepspeed:`
// form (step_speed.h), which replaces it, and the step form's completion relay
// (docs/motion.md "Step-count ramps (stepspeed:)").
#include "plc_cell/motion/axis_config.h"
#include "plc_cell/motion/axis_state.h"

namespace plc_cell {

class Memory;

namespace motion {

struct Ramp {
  double start, max, acc, dec;  // Hz, Hz, Hz/s, Hz/s
};

class Ramps {
 public:
  Ramps(const AxesConfig& cfg, const AxisStates& axes, Memory& mem) : cfg_(cfg), axes_(axes), mem_(mem) {}

  Ramp of(int ps) const;
  // The step form has one speed: a step's SPD is not read, nor followed (R4056).
  bool step_form(int ps) const { return cfg_.axes[ps].stepspeed.used; }
  // The `stepspeed:` completion relay of axis ps, if it has one.
  void set_done(int ps, bool on) const;

 private:
  const AxesConfig& cfg_;
  const AxisStates& axes_;
  Memory& mem_;
};

}  // namespace motion
}  // namespace plc_cell
