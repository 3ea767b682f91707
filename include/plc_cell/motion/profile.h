#pragma once
// The speed profile of one move, in closed form: piecewise-constant acceleration
// segments (trapezoid, automatic triangle on short strokes, decelerated stop).
// Pulse k (1..N) is emitted at the instant the continuous position s(t) reaches k;
// the move ends with pulse N. Everything is evaluated analytically: the cost of a
// query does not depend on the frequency (docs/motion.md "Profiles").
#include <cstdint>
#include <limits>
#include <vector>

namespace plc_cell {
namespace motion {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Segment {
  double t0 = 0;  // s from the move's start
  double s0 = 0;  // pulses at t0
  double v0 = 0;  // Hz at t0
  double a = 0;   // Hz/s over the segment
};

class Profile {
 public:
  Profile() = default;
  // A move of n pulses (n < 0: endless) that starts at v_in, runs toward v_target
  // and ends at v_out (DRV: the start/stop speed; DRVC: v_target, no stop).
  // acc/dec in Hz/s (kInf: a step change). A stroke too short to reach v_target
  // peaks lower (triangle); one too short to slow to v_out ends faster.
  static Profile plan(int64_t n, double v_in, double v_target, double v_out, double acc, double dec);
  // The rest of a move from (s, v) decelerating at dec to v_stop, ending on the next
  // whole pulse: what a decelerated stop (M1991) emits. n_limit caps it (the
  // move's own end).
  static Profile stop(double v, double v_stop, double dec, int64_t n_limit);
  // The same motion scaled in distance by k (speeds and accelerations too), with the
  // same duration, as n pulses: a FUN147 axis following the lead axis's profile.
  Profile scaled(double k, int64_t n) const;

  int64_t pulses() const { return n_; }      // -1: endless
  bool endless() const { return n_ < 0; }
  double duration() const { return t_end_; }  // s; kInf when endless
  double peak() const { return peak_; }
  double end_speed() const { return v_end_; }
  const std::vector<Segment>& segments() const { return seg_; }

  double position(double t) const;  // continuous pulses at t (clamped to [0, n])
  double velocity(double t) const;  // Hz at t (0 after the end)
  double time_of(double s) const;   // instant s(t) = s (s <= n)
  // Pulses emitted by t: floor(s(t)), exactly n from duration() on.
  int64_t emitted(double t) const;

 private:
  void add(double dt, double v0, double a);
  std::vector<Segment> seg_;
  int64_t n_ = 0;
  double t_end_ = 0, peak_ = 0, v_end_ = 0;
};

}  // namespace motion
}  // namespace plc_cell
