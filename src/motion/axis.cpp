// One pulse output in virtual time.
#include "plc_cell/motion/axis.h"

#include <algorithm>
#include <cmath>

namespace plc_cell {
namespace motion {

void Axis::start(uint64_t t, int64_t delta, int64_t comp, bool forward, const Profile& prof) {
  if (active_) settle(t);
  active_ = true;
  forward_ = forward;
  t0_ = t;
  len_ = delta < 0 ? -delta : delta;
  sign_ = delta < 0 ? -1 : 1;
  comp_ = comp;
  prof_ = prof;
  ++epoch_;
}

int64_t Axis::progress(int64_t e) const {
  if (prof_.endless()) return e;
  if (comp_ >= 0) return std::clamp<int64_t>(e - comp_, 0, len_);
  return e >= prof_.pulses() ? len_ : std::min(e, len_);  // negative compensation: fewer pulses
}

uint64_t Axis::end_ns() const {
  if (!active_ || prof_.endless()) return kNever;
  return t0_ + static_cast<uint64_t>(std::ceil(prof_.duration() * 1e9 - 1e-6));
}

int64_t Axis::emitted(uint64_t t) const {
  if (!active_) return 0;
  if (t >= end_ns()) return prof_.pulses();
  return prof_.emitted(secs(t));
}

int64_t Axis::position(uint64_t t) const {
  if (!active_) return pos0_;
  return pos0_ + sign_ * progress(emitted(t));
}

double Axis::frequency(uint64_t t) const {
  if (!active_ || t >= end_ns()) return 0;
  return prof_.velocity(secs(t));
}

int64_t Axis::remaining(uint64_t t) const {
  if (!active_ || prof_.endless()) return 0;
  return len_ - progress(emitted(t));
}

int64_t Axis::pulse_count(uint64_t t) const {
  return count0_ + (forward_ ? 1 : -1) * emitted(t);
}

uint64_t Axis::when_at(int64_t pos) const {
  if (!active_) return kNever;
  const int64_t k = (pos - pos0_) * sign_;  // logical pulses from t0
  if (k <= 0) return kNever;
  const int64_t e = comp_ > 0 ? k + comp_ : k;  // pulses to emit for it
  if (!prof_.endless() && (k > len_ || e > prof_.pulses())) return kNever;
  if (!prof_.endless() && e == prof_.pulses()) return end_ns();
  const double secs = prof_.time_of(static_cast<double>(e));
  if (!(secs < 1e9)) return kNever;  // beyond ~30 years of virtual time (an open-ended switch)
  return t0_ + static_cast<uint64_t>(std::ceil(secs * 1e9 - 1e-6));
}

void Axis::settle(uint64_t t) {
  if (!active_) return;
  const int64_t e = committed(t);
  count0_ += (forward_ ? 1 : -1) * e;
  pos0_ += sign_ * progress(e);
  travel0_ += e;
  active_ = false;
  ++epoch_;
}

uint64_t Axis::step_time(int64_t j, int64_t per) const {
  if (!active_) return kNever;
  if (j <= 0) return t0_;
  if (!prof_.endless() && j >= prof_.pulses() * per) return j == prof_.pulses() * per ? end_ns() : kNever;
  const double s = prof_.time_of(static_cast<double>(j) / static_cast<double>(per));
  if (!(s < 1e9)) return kNever;
  return t0_ + static_cast<uint64_t>(std::ceil(s * 1e9 - 1e-6));  // as end_ns() and when_at()
}

int64_t Axis::steps(uint64_t t, int64_t per) const {
  if (!active_ || t <= t0_) return 0;
  const int64_t cap = prof_.endless() ? INT64_MAX : prof_.pulses() * per;
  if (t >= end_ns()) return cap;
  // The float estimate is off by at most one near a boundary; step_time decides.
  int64_t j = static_cast<int64_t>(std::floor(prof_.position(secs(t)) * static_cast<double>(per)));
  j = std::clamp<int64_t>(j, 0, cap);
  while (j < cap && step_time(j + 1, per) <= t) ++j;
  while (j > 0 && step_time(j, per) > t) --j;
  return j;
}

int64_t Axis::committed(uint64_t t) const {
  if (!active_) return 0;
  if (t >= end_ns()) return prof_.pulses();
  const int64_t e = (steps(t, 4) + 2) / 4;  // quarters: past k - 1/2 is pulse k
  return prof_.endless() ? e : std::min(e, prof_.pulses());
}

void Axis::cut(uint64_t t) { settle(t); }

void Axis::retarget(uint64_t t, double v_target, double v_out, double acc, double dec) {
  if (!active_) return;
  const double v = frequency(t);
  const int64_t e = committed(t);
  const bool endless = prof_.endless();
  const int64_t left = endless ? -1 : prof_.pulses() - e;
  const int64_t comp_left = std::max<int64_t>(0, comp_ - e);
  const int64_t len_left = left_if_cut(t);
  settle(t);
  if (left == 0) return;
  active_ = true;
  t0_ = t;
  comp_ = comp_left;
  len_ = len_left;
  prof_ = Profile::plan(left, v > 0 ? v : std::min(v_out, v_target), v_target, v_out, acc, dec);
}

void Axis::decelerate(uint64_t t, double v_stop, double dec) {
  if (!active_) return;
  const double v = frequency(t);
  const int64_t e = committed(t);
  const int64_t left = prof_.endless() ? -1 : prof_.pulses() - e;
  const int64_t comp_left = std::max<int64_t>(0, comp_ - e);
  const int64_t len_left = left_if_cut(t);
  settle(t);
  if (v <= 0 || left == 0) return;
  active_ = true;
  t0_ = t;
  comp_ = comp_left;
  len_ = len_left > 0 || !prof_.endless() ? len_left : 0;
  const Profile p = Profile::stop(v, v_stop, dec, left);
  if (prof_.endless()) len_ = p.pulses();
  prof_ = p;
}

}  // namespace motion
}  // namespace plc_cell
