#pragma once
// The simulated switches of the cell YAML's `axes:` (DOG, limits, PG0): inputs X that
// the axis positions drive (docs/motion.md "Cell YAML"). An input no switch drives is
// the X image.
#include <cstdint>

#include "plc_cell/motion/axis_config.h"
#include "plc_cell/motion/axis_state.h"

namespace plc_cell {

class Memory;

namespace motion {

class Switches {
 public:
  Switches(const AxesConfig& cfg, const AxisStates& axes, Memory& mem) : cfg_(cfg), axes_(axes), mem_(mem) {}

  // The level of input Xx at t: any switch on it that is on, else the X image.
  bool input(int x, uint64_t t) const;
  // The switches' levels at t into the X image.
  void write(uint64_t t) const;

 private:
  const AxesConfig& cfg_;
  const AxisStates& axes_;
  Memory& mem_;
};

}  // namespace motion
}  // namespace plc_cell
