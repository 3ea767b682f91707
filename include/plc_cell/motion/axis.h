#pragma once
// One pulse output (PSO0-PSO3) in virtual time: the logical position (DR4088),
// the move in progress as a closed-form Profile, its pulses, frequency and end.
// Nothing here is sampled per pulse: every query is O(1) in the pulse rate.
#include <cstdint>

#include "plc_cell/motion/profile.h"

namespace plc_cell {
namespace motion {

constexpr uint64_t kNever = UINT64_MAX;

class Axis {
 public:
  // Starts a move at t: the logical position changes by `delta` (sign = position
  // direction); `comp` extra pulses (backlash/compensation) come first and do not
  // change the logical position; `prof` emits |delta| + comp pulses (or is endless).
  // `forward` is the pulse direction (U/D output, P/R direction level).
  void start(uint64_t t, int64_t delta, int64_t comp, bool forward, const Profile& prof);
  // Stops at t at once: pulses emitted so far stay, the rest is dropped. A pulse
  // whose rising edge has left the pin (past half its period) is completed, so the
  // pins and a counter wired to them agree with the position (committed()).
  void cut(uint64_t t);
  // Replaces the rest of the move by a deceleration at dec (Hz/s) to v_stop.
  void decelerate(uint64_t t, double v_stop, double dec);
  // Changes the rest of the move at t to a new target speed (R4056 = 5AH): from the
  // current speed toward v_target, ending at v_out, over the pulses left.
  void retarget(uint64_t t, double v_target, double v_out, double acc, double dec);
  // Settles a finished move (call at or after end_ns()).
  void settle(uint64_t t);

  bool moving() const { return active_; }
  uint64_t end_ns() const;                 // kNever when idle or endless
  int64_t position(uint64_t t) const;      // logical position, pulses
  int64_t idle_position() const { return pos0_; }  // position() while not moving
  double frequency(uint64_t t) const;      // Hz (0 when idle)
  int64_t remaining(uint64_t t) const;     // logical pulses still to go (0 when endless)
  int64_t emitted(uint64_t t) const;       // pulses of this move so far
  int64_t pulse_count(uint64_t t) const;   // all pulses ever, signed by direction (encoder)
  bool forward() const { return forward_; }
  bool endless() const { return active_ && prof_.endless(); }
  const Profile& profile() const { return prof_; }
  uint64_t start_ns() const { return t0_; }

  // ---- pulse edges (docs/motion.md "Pulse pins"), O(1) in the pulse rate ----
  // Pulses a cut at t keeps: pulse k counts once the move is past k - 1/2.
  int64_t committed(uint64_t t) const;
  // Logical pulses a cut at t would leave undone (DR4072 after the cut).
  int64_t left_if_cut(uint64_t t) const { return active_ && !prof_.endless() ? len_ - progress(committed(t)) : 0; }
  // The instant this move has travelled j/per pulses (j = 0: its start; the last
  // pulse: end_ns()); kNever beyond the move or when idle.
  uint64_t step_time(int64_t j, int64_t per) const;
  // How many of those instants (j >= 1) are <= t: floor(per * travel), exactly
  // consistent with step_time.
  int64_t steps(uint64_t t, int64_t per) const;
  int64_t travel0() const { return travel0_; }  // pulses of all earlier moves (unsigned)
  int64_t count0() const { return count0_; }    // pulse_count at this move's start
  // Changes at every start and settle: the pins' model is new.
  uint64_t epoch() const { return epoch_; }

  // The instant the logical position reaches pos on this move (kNever if it does not).
  uint64_t when_at(int64_t pos) const;
  int direction() const { return sign_; }  // of the logical position

  void set_position(int64_t p) { pos0_ = p; }  // the ladder (or homing) writes DR4088

 private:
  double secs(uint64_t t) const { return t <= t0_ ? 0.0 : double(t - t0_) * 1e-9; }
  int64_t progress(int64_t e) const;  // logical pulses done after e emitted

  bool active_ = false;
  bool forward_ = true;
  uint64_t t0_ = 0;
  int64_t pos0_ = 0;    // logical position at t0_
  int64_t len_ = 0;     // |delta|
  int sign_ = 1;        // position direction
  int64_t comp_ = 0;
  int64_t count0_ = 0;  // pulse_count at t0_
  int64_t travel0_ = 0;  // pulses of all earlier moves, either direction
  uint64_t epoch_ = 0;
  Profile prof_;
};

}  // namespace motion
}  // namespace plc_cell
