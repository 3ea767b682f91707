#include "plc_cell/sim/input_signal.h"

#include "plc_cell/core/memory.h"

namespace plc_cell {

bool StepSignal::level(uint64_t t, const Memory&) {
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
