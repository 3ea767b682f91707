#include "plc_cell/hsc/measured_input.h"

namespace plc_cell {
namespace hsc {

void MeasuredInput::start(uint64_t) {
  meter_.reset();
  src_ = nullptr;  // taken again at the first step
}

// A source's jump is one edge of the measured pin if its level changed.
void MeasuredInput::settle() {
  const InputPin& p = pins_[x_];
  if (!src_ || src_ != p.src || src_->epoch() == epoch_) return;
  q_ = src_->quarter(ctx_.now());
  const bool level = src_->level(p.phase, q_);
  if (level != level_ && !p.blocked()) meter_.edge(ctx_.now(), level);
  level_ = level;
  epoch_ = src_->epoch();
}

// The edges of an analytic pin in (now, t]: the source is in one state over the span, so
// each boundary's instant is exact. Two cycles (8 quarters) hold the last full cycle,
// which is all a meter keeps; earlier boundaries are skipped.
void MeasuredInput::advance_to(uint64_t t) {
  const InputPin& p = pins_[x_];
  const EdgeSource* s = p.src;
  if (s != src_) {  // attached, detached, or the first step of a run
    src_ = s;
    if (s) {
      q_ = s->quarter(ctx_.now());
      level_ = s->level(p.phase, q_);
      epoch_ = s->epoch();
    }
  }
  if (!s) return;
  const int64_t q1 = s->quarter(t);
  if (q1 == q_) return;
  const int64_t dir = q1 > q_ ? 1 : -1;
  const int64_t from = (q1 - q_) * dir > 8 ? q1 - 8 * dir : q_;
  const bool lost = p.blocked();  // a source faster than the filter leaves the input OFF
  for (int64_t q = from; q != q1; q += dir) {
    const bool a = s->level(p.phase, q), b = s->level(p.phase, q + dir);
    if (a != b && !lost) meter_.edge(s->time_of_quarter(q + dir, ctx_.now()), b);
  }
  q_ = q1;
  level_ = s->level(p.phase, q1);
}

void MeasuredInput::input_edges(uint64_t t, const InputLevels& before, const InputLevels& after) {
  if (before[x_] != after[x_]) meter_.edge(t, after[x_]);
}

}  // namespace hsc
}  // namespace plc_cell
