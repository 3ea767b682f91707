// The speeds and rates of the FUN140 moves: FUN141's ramp or the `stepspeed:` form.
#include "plc_cell/motion/ramps.h"

#include "plc_cell/core/memory.h"

namespace plc_cell {
namespace motion {

Ramp Ramps::of(int ps) const {
  const StepSpeed& ss = cfg_.axes[ps].stepspeed;
  if (ss.used) return {ss.start_hz(), ss.max_hz(), ss.accel(), ss.accel()};
  const AxisParams& par = axes_[ps].params;
  return {par.start_hz(), par.max_hz(), par.acc_hz_per_s(), par.dec_hz_per_s()};
}

void Ramps::set_done(int ps, bool on) const {
  const int m = cfg_.axes[ps].stepspeed.done;
  if (cfg_.axes[ps].stepspeed.used && m >= 0) mem_.set_bit(Area::M, static_cast<uint32_t>(m), on);
}

}  // namespace motion
}  // namespace plc_cell
