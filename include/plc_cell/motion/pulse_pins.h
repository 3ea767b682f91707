#pragma once
// The two output pins of a pulse axis (Y2n, Y2n+1) and an encoder on its load, as
// exact functions of virtual time (docs/motion.md "Pulse pins"). Both are computed
// from the axis's closed-form profile: a pin level or the instant of the k-th edge
// costs O(1) in the pulse rate (a root of the profile), never a walk over pulses.
//
// Pulse k of a move (1..N) occupies travel s in (k-1, k]: its pin is at the active
// level for s in [k-1/2, k) (leading edge at k-1/2, trailing edge at k, the profile's
// pulse instant), so every pulse is half a period wide and the pins rest at the
// normal level between moves. In quarter terms (what the counters use):
//   U/D, P/R: Q = 4*(pulses of all earlier moves) + 2 + floor(4 s) (always rising);
//             the pulse pin is active for Q mod 4 in {0, 1}.
//   A/B, encoder: Q = 4*m*(signed pulse count) + 2 +- (quarters of this move), m the
//             encoder periods per pulse; A = Q mod 4 in {0, 1}, B = Q mod 4 in {1, 2}:
//             A leads B moving forward, and the rest state is A off, B on.
#include <string>

#include "plc_cell/hsc/edge_source.h"
#include "plc_cell/motion/axis.h"
#include "plc_cell/motion/axis_config.h"

namespace plc_cell {
namespace motion {

struct PinLevels {
  bool first = false, second = false;  // Y2n, Y2n+1 (encoder: A, B)
};

class AxisSignal : public hsc::EdgeSource {
 public:
  // The output pins of an axis in `mode` with `polarity`. dir_on_negative: the P/R
  // direction pin is ON for backward pulses (the stepper form, `stepspeed:`), not up.
  static AxisSignal pins(std::string name, const Axis* ax, OutputMode mode, Polarity polarity,
                         bool dir_on_negative = false);
  // An encoder on the load with `periods` A/B periods per output pulse.
  static AxisSignal encoder(std::string name, const Axis* ax, int64_t periods);

  PinLevels levels(uint64_t t) const;
  // Leading / trailing edge instant of pulse k (1..N) of the present move (kNever
  // beyond it): the leading edge is where a rising-edge counter counts it.
  uint64_t leading_edge(int64_t k) const { return ax_->step_time(4 * k - 2, 4); }
  uint64_t trailing_edge(int64_t k) const { return ax_->step_time(k, 1); }
  // The first instant after t at which a level changes (kNever: none in this move).
  uint64_t next_edge(uint64_t t) const;

  // hsc::EdgeSource
  const std::string& name() const override { return name_; }
  int64_t quarter(uint64_t t) const override;
  int direction() const override;
  uint64_t time_of_quarter(int64_t q, uint64_t from) const override;
  bool level(int phase, int64_t q) const override;
  double rate_hz() const override;
  uint64_t epoch() const override { return ax_->epoch(); }

 private:
  enum class Kind { Pulses, Quadrature };
  AxisSignal(std::string name, const Axis* ax, Kind k, OutputMode m, Polarity p, int64_t per)
      : name_(std::move(name)), ax_(ax), kind_(k), mode_(m), invert_(p == Polarity::NormalOn), per_(per) {}
  bool dir_on_negative_ = false;
  int64_t base() const;        // Q at the start of the present move
  int64_t quarters() const { return 4 * per_; }  // quarter steps per pulse

  std::string name_;
  const Axis* ax_;
  Kind kind_;
  OutputMode mode_;
  bool invert_;
  int64_t per_;  // encoder periods per pulse (1 for the pins)
};

}  // namespace motion
}  // namespace plc_cell
