#pragma once
// The profile component's planning of one FUN140 move step (DRVA, DRV, DRVC): from the
// step's stroke to the change of the logical position, the pulses with the backlash
// and direction compensation (P7, P10, P11), the direction, and the speed profile
// with the DRVC chaining (docs/motion.md "FUN140", "Profiles").
#include <cstdint>

#include "plc_cell/motion/params.h"
#include "plc_cell/motion/profile.h"
#include "plc_cell/motion/ramps.h"
#include "plc_cell/motion/table.h"

namespace plc_cell {
namespace motion {

struct StepMove {
  int64_t delta = 0;     // change of the logical position (endless: its sign only)
  int64_t comp = 0;      // compensation pulses, sent first
  int64_t pulses = 0;    // |delta| + comp; -1: endless
  bool forward = true;   // pulse direction
  bool endless = false;  // DRV with a stroke of 0
};

// The move of step s for a stroke (Ut or pulses) from position; a DRVC chain keeps its
// direction. 0, or the error code: 33 the stroke is out of range, 40 the move is too long.
int plan_step_move(const Step& s, int64_t stroke, const AxisParams& par, int64_t position, bool chain,
                   bool chain_forward, StepMove* out);

// The speed profile of move m at speed_hz: from the start speed, or inside a DRVC chain
// from the previous section's end speed; ending at the start speed, or for a DRVC
// section at its own speed.
Profile step_profile(const StepMove& m, const Ramp& rp, double speed_hz, bool chain, double chain_speed, bool drvc);

}  // namespace motion
}  // namespace plc_cell
