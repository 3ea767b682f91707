#pragma once
// What the manual promises about a wired axis (cell_generator.h), checked while a
// generated cell runs. A violation aborts with the axis, step and both figures, so
// libFuzzer keeps the input as a finding.
#include <cstdint>
#include <vector>

#include "cell_generator.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell_fuzz {

class WiredAxisCheck {
 public:
  // Observes step ends through the motion unit; call before RUN.
  WiredAxisCheck(plc_cell::SoftCell& cell, const std::vector<WiredAxis>& axes);
  // After the run: for every axis standing still, DR4088+2Ps equals the position and,
  // if the axis never homed (homing reloads DR4088 with P16), the HSC wired to its pins
  // counted exactly the pulses (mod 2^32: the counter is a 32-bit register).
  void check_at_rest();
  uint64_t steps_checked() const { return steps_checked_; }

 private:
  void step_done(int ps, int step, uint64_t t_ns);

  plc_cell::SoftCell& cell_;
  std::vector<WiredAxis> axes_;
  int64_t baseline_[4] = {};
  uint64_t steps_checked_ = 0;
};

}  // namespace plc_cell_fuzz
