#include "plc_cell/hsc/pulse_meter.h"

namespace plc_cell {
namespace hsc {

void PulseMeter::reset() {
  have_rise_ = have_fall_ = false;
  rise_ = fall_ = width_ = period_ = 0;
}

// Before a first period an automatic timeout has nothing to scale with: the first
// cycle is measured however long it is.
bool PulseMeter::expired(uint64_t now_ns) const {
  if (!have_rise_) return false;
  const uint64_t limit = timeout_ns_ ? timeout_ns_ : 2 * period_;
  if (limit == 0) return false;
  return now_ns - rise_ > limit;
}

void PulseMeter::edge(uint64_t t_ns, bool level) {
  if (!level) {
    if (have_rise_) {
      fall_ = t_ns;
      have_fall_ = true;
    }
    return;
  }
  if (expired(t_ns)) {
    width_ = period_ = 0;  // the signal had stopped: this edge is a first edge again
  } else if (have_rise_ && have_fall_) {
    width_ = fall_ - rise_;
    period_ = t_ns - rise_;
  }
  rise_ = t_ns;
  have_rise_ = true;
  have_fall_ = false;
}

PulseReading PulseMeter::read(uint64_t now_ns) const {
  PulseReading r;
  if (period_ == 0 || expired(now_ns)) return r;
  r.width_ns = width_;
  r.period_ns = period_;
  r.frequency_hz = 1e9 / double(period_);
  return r;
}

}  // namespace hsc
}  // namespace plc_cell
