// The pins of a pulse axis and an encoder on its load, in virtual time.
#include "plc_cell/motion/pulse_pins.h"

namespace plc_cell {
namespace motion {

namespace {
int mod4(int64_t q) { return static_cast<int>(((q % 4) + 4) % 4); }
bool phase_a(int64_t q) { return mod4(q) <= 1; }
bool phase_b(int64_t q) { return mod4(q) == 1 || mod4(q) == 2; }
}  // namespace

AxisSignal AxisSignal::pins(std::string name, const Axis* ax, OutputMode mode, Polarity polarity,
                            bool dir_on_negative) {
  AxisSignal s(std::move(name), ax, mode == OutputMode::AB ? Kind::Quadrature : Kind::Pulses, mode, polarity, 1);
  s.dir_on_negative_ = dir_on_negative;
  return s;
}

AxisSignal AxisSignal::encoder(std::string name, const Axis* ax, int64_t periods) {
  return AxisSignal(std::move(name), ax, Kind::Quadrature, OutputMode::AB, Polarity::NormalOff, periods);
}

int64_t AxisSignal::base() const {
  if (kind_ == Kind::Pulses) return 4 * ax_->travel0() + 2;
  return quarters() * ax_->count0() + 2;
}

int AxisSignal::direction() const {
  if (!ax_->moving()) return 0;
  return kind_ == Kind::Pulses || ax_->forward() ? 1 : -1;
}

// Forward the quarter boundaries are taken at the instants (floor); backward the
// same boundaries are left just after them (the time-reverse: A falls where it
// rose going forward, at s = k - 1/2, as the cut rule Axis::committed expects).
int64_t AxisSignal::quarter(uint64_t t) const {
  if (direction() >= 0) return base() + ax_->steps(t, quarters());
  if (t <= ax_->start_ns()) return base();
  const int64_t cap = ax_->profile().endless() ? INT64_MAX : ax_->profile().pulses() * quarters();
  const int64_t b = ax_->steps(t - 1, quarters()) + 1;  // #{j >= 0 : step_time(j) < t}
  return base() - std::min(b, cap);
}

uint64_t AxisSignal::time_of_quarter(int64_t q, uint64_t from) const {
  const int dir = direction();
  if (dir == 0) return kNever;
  const int64_t j = (q - base()) * dir;  // quarter steps of this move
  if (j <= 0) return from;
  const uint64_t t = dir > 0 ? ax_->step_time(j, quarters()) : ax_->step_time(j - 1, quarters());
  if (t == kNever) return kNever;
  const uint64_t at = dir > 0 ? t : t + 1;
  return at < from ? from : at;
}

bool AxisSignal::level(int phase, int64_t q) const {
  if (kind_ == Kind::Quadrature) return (phase == 0 ? phase_a(q) : phase_b(q)) != invert_;
  const bool pulse = phase_a(q);
  const bool up = ax_->forward();
  if (mode_ == OutputMode::PR) return phase == 0 ? pulse != invert_ : up != dir_on_negative_;  // ON = up, or down
  return (phase == 0 ? up && pulse : !up && pulse) != invert_;           // U/D
}

double AxisSignal::rate_hz() const {
  return ax_->moving() ? ax_->profile().peak() * static_cast<double>(per_) : 0.0;
}

PinLevels AxisSignal::levels(uint64_t t) const {
  const int64_t q = quarter(t);
  return {level(0, q), level(1, q)};
}

uint64_t AxisSignal::next_edge(uint64_t t) const {
  const int dir = direction();
  if (dir == 0) return kNever;
  const int64_t q = quarter(t);
  for (int i = 1; i <= 4; ++i) {
    const int64_t a = q + (i - 1) * dir, b = q + i * dir;
    if (level(0, a) != level(0, b) || level(1, a) != level(1, b)) {
      const uint64_t at = time_of_quarter(b, t + 1);
      return at;
    }
  }
  return kNever;
}

}  // namespace motion
}  // namespace plc_cell
