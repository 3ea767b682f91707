// A FUN140 move step's pulses, direction and speed profile.
#include "plc_cell/motion/move_plan.h"

#include <algorithm>
#include <cstdlib>

namespace plc_cell {
namespace motion {

int plan_step_move(const Step& s, int64_t stroke, const AxisParams& par, int64_t position, bool chain,
                   bool chain_forward, StepMove* out) {
  if (stroke < -99999999 || stroke > 99999999) return 33;
  const int64_t pulses = s.ut ? par.ut_to_pulses(stroke) : stroke;
  const bool rot = par.p9_rot != 0;
  int64_t delta;  // change of the logical position
  bool forward;
  bool endless = false;
  if (s.abs) {
    delta = pulses - position;
    forward = (delta > 0) != rot;
  } else {
    endless = pulses == 0;
    forward = s.dir > 0 || (s.dir == 0 && pulses >= 0);
    if (chain) forward = chain_forward;
    const int64_t len = pulses < 0 ? -pulses : pulses;
    delta = forward != rot ? len : -len;
    if (endless) delta = forward != rot ? 1 : -1;  // the direction only
  }
  if (std::llabs(delta) > 2147483647LL) return 40;
  out->delta = delta;
  out->forward = forward;
  out->endless = endless;
  out->comp = forward ? par.p10_fwd_comp : int64_t(par.p7_backlash) + par.p11_bwd_comp;
  out->pulses = endless ? -1 : std::llabs(delta) + out->comp;
  return 0;
}

Profile step_profile(const StepMove& m, const Ramp& rp, double speed_hz, bool chain, double chain_speed, bool drvc) {
  const double f0 = rp.start;
  const double v_in = chain ? std::min(chain_speed, std::max(speed_hz, chain_speed)) : std::min(f0, speed_hz);
  const double v_out = drvc ? speed_hz : f0;
  return Profile::plan(m.pulses, v_in, speed_hz, v_out, rp.acc, rp.dec);
}

}  // namespace motion
}  // namespace plc_cell
