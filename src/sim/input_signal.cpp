#include "plc_cell/sim/input_signal.h"

#include "plc_cell/core/memory.h"

namespace plc_cell {

// The last pulse that starts before t1 is the only candidate: earlier ones end earlier.
bool PulseSignal::on_between(uint64_t t0, uint64_t t1) const {
  if (period_ == 0 || width_ == 0 || t1 <= delay_) return false;
  const uint64_t start = delay_ + (t1 - 1 - delay_) / period_ * period_;
  return start + width_ > t0;
}

bool StepSignal::level(uint64_t t, const Memory&) { return at(t); }

bool StepSignal::on_between(uint64_t t0, uint64_t t1) const {
  if (at(t0)) return true;  // ON from t0 on, until the next step
  for (const auto& s : steps_)
    if (s.first > t0 && s.first < t1 && s.second) return true;
  return false;
}

bool StepSignal::at(uint64_t t) const {
  bool v = false;
  for (const auto& s : steps_) {
    if (s.first > t) break;
    v = s.second;
  }
  return v;
}

bool FollowSignal::level(uint64_t t, const Memory& mem) {
  const bool src = mem.bit(source_.area, source_.index) != invert_;
  if (src != state_) {
    if (!pending_ || target_ != src) {
      pending_ = true;
      target_ = src;
      due_ = t + (src ? on_delay_ : off_delay_);
    }
  } else {
    pending_ = false;
  }
  if (pending_ && t >= due_) {
    state_ = target_;
    pending_ = false;
  }
  return state_;
}

}  // namespace plc_cell
