#pragma once
// Signals that the simulated cell presents on input terminals, as functions of time.
#include <cstdint>
#include <deque>
#include <memory>
#include <utility>
#include <vector>

#include "plc_cell/core/address.h"

namespace plc_cell {

class Memory;

class InputSignal {
 public:
  virtual ~InputSignal() = default;
  // Level at time t_us; may read PLC memory (outputs the signal follows).
  virtual bool level(uint64_t t_us, const Memory& mem) = 0;
  // Was the level ON at some instant in the open interval (t0_us, t1_us)? For a
  // capture input, which sees a pulse between two scans. Signals that change only
  // when evaluated (at the scans) never are.
  virtual bool on_between(uint64_t /*t0_us*/, uint64_t /*t1_us*/) const { return false; }
};

// On for width_us out of every period_us, starting at delay_us.
class PulseSignal : public InputSignal {
 public:
  PulseSignal(uint64_t period_us, uint64_t width_us, uint64_t delay_us)
      : period_(period_us), width_(width_us), delay_(delay_us) {}
  bool level(uint64_t t, const Memory&) override {
    return t >= delay_ && (t - delay_) % period_ < width_;
  }
  bool on_between(uint64_t t0, uint64_t t1) const override;

 private:
  uint64_t period_, width_, delay_;
};

// A fixed timeline: (time, level) pairs in increasing time; level 0 before the first.
class StepSignal : public InputSignal {
 public:
  explicit StepSignal(std::vector<std::pair<uint64_t, bool>> steps) : steps_(std::move(steps)) {}
  bool level(uint64_t t, const Memory&) override;
  bool on_between(uint64_t t0, uint64_t t1) const override;

 private:
  bool at(uint64_t t) const;
  std::vector<std::pair<uint64_t, bool>> steps_;
};

// Follows a discrete (an actuator's output) after a delay: a cylinder and its end switch.
class FollowSignal : public InputSignal {
 public:
  FollowSignal(Address source, uint64_t on_delay_us, uint64_t off_delay_us, bool invert)
      : source_(source), on_delay_(on_delay_us), off_delay_(off_delay_us), invert_(invert) {}
  bool level(uint64_t t, const Memory& mem) override;

 private:
  Address source_;
  uint64_t on_delay_, off_delay_;
  bool invert_;
  bool state_ = false;
  bool pending_ = false;
  bool target_ = false;
  uint64_t due_ = 0;
};

}  // namespace plc_cell
