#include "plc_cell/hsc/hsc_counter.h"

#include <string>

#include "plc_cell/core/error.h"
#include "plc_cell/core/interrupt_sources.h"

namespace plc_cell {
namespace hsc {

int counter_source(int n) { return n < 4 ? irq::kHsc0I + n : irq::kHsc4I + (n - 4); }

HscCounter::HscCounter(UnitContext& ctx, const InputPins& pins, int n, const CounterDef& def, uint64_t window_us)
    : ctx_(ctx), pins_(pins), n_(n), def_(def), window_ns_(window_us * 1000), dec_(def.mode, def.decoding) {}

void HscCounter::bind() {
  src_ = nullptr;
  phase_[0] = phase_[1] = -1;
  if (!def_.used || def_.timer) return;
  for (int k = 0; k < 2; ++k) {
    const int x = k == 0 ? def_.pin_a : def_.pin_b;
    if (x < 0 || !pins_[x].src) continue;
    if (src_ && src_ != pins_[x].src)
      throw Error("HSC" + std::to_string(n_) + ": its counting inputs are driven by two sources (" + src_->name() +
                  ", " + pins_[x].src->name() + "); give it one encoder");
    src_ = pins_[x].src;
    phase_[k] = pins_[x].phase;
  }
  for (int x : {def_.pin_mask, def_.pin_clear})
    if (x >= 0 && pins_[x].src)
      throw Error("HSC" + std::to_string(n_) + ": X" + std::to_string(x) +
                  " is a MASK/CLEAR input; pulse sources drive counting or interrupt inputs only");
  if (ctx_.running() && src_) take_quarter();
}

bool HscCounter::blocked() const {
  for (int k = 0; k < 2; ++k) {
    const int x = k == 0 ? def_.pin_a : def_.pin_b;
    if (phase_[k] >= 0 && pins_[x].blocked()) return true;
  }
  return false;
}

bool HscCounter::cleared(const InputLevels& term) const {
  return (def_.pin_clear >= 0 && term[def_.pin_clear] != def_.inv_clear) || sw_clear_;
}

bool HscCounter::counting(const InputLevels& term) const {
  if (!def_.used || def_.timer || cleared(term)) return false;
  if ((def_.pin_mask >= 0 && term[def_.pin_mask] != def_.inv_mask) || sw_mask_) return false;
  if (n_ >= 4 && !ctx_.irq().enabled(counter_source(n_))) return false;  // a disabled SHSC stops counting
  return true;
}

Pins HscCounter::pins_at(int64_t q, const InputLevels& term) const {
  auto lvl = [&](int pin, int ph) { return ph >= 0 ? src_->level(ph, q) : term[pin]; };
  Pins p;
  p.a = lvl(def_.pin_a, phase_[0]) != def_.inv_count;
  if (def_.pin_b >= 0) p.b = lvl(def_.pin_b, phase_[1]) != def_.inv_count;
  else if (def_.mode == Mode::PR || def_.mode == Mode::PRx2) p.b = sw_dir_;
  return p;
}

void HscCounter::window(int dir, CountDecoder::Window* w) const {
  for (int i = 0; i <= dec_.span(); ++i) (*w)[i] = pins_at(q_ + i * dir, pins_.levels());
}

uint32_t HscCounter::cv() const { return n_ < 4 ? cv_ : ctx_.reg32(cv_register(n_)); }
uint32_t HscCounter::pv() const { return n_ < 4 ? pv_ : ctx_.reg32(pv_register(n_)); }

void HscCounter::set_cv(uint32_t v) {
  if (n_ < 4) cv_ = v;
  else ctx_.set_reg32(cv_register(n_), v);
}

void HscCounter::add_count(int64_t d, bool check) {
  if (d == 0) return;
  const uint32_t v = cv() + static_cast<uint32_t>(d);
  set_cv(v);
  total_ += d;
  if (check && v == pv()) ctx_.match(counter_source(n_), n_, def_.timer, ctx_.now());
}

void HscCounter::take_quarter() {
  q_ = src_->quarter(ctx_.now());
  last_ = pins_at(q_, pins_.levels());
  epoch_ = src_->epoch();
}

// The source changed at now (a move started, was cut or ended): its levels before and
// after are one transition of the counting inputs. Counts are exact through a cut too,
// since an axis completes a pulse whose edge has left the pin (docs/motion.md "Pulse pins").
void HscCounter::resync() {
  const int64_t q = src_->quarter(ctx_.now());
  const Pins now = pins_at(q, pins_.levels());
  const int d = dec_.step(last_, now);
  if (counting(pins_.levels()) && !blocked()) add_count(d, true);
  q_ = q;
  last_ = now;
  epoch_ = src_->epoch();
}

void HscCounter::start(uint64_t) {
  cv_ = pv_ = 0;
  sw_mask_ = sw_clear_ = sw_dir_ = false;
  total_ = 0;
  hist_.clear();
  dec_.reset();
  if (src_) take_quarter();
}

void HscCounter::settle() {
  if (src_ && src_->epoch() != epoch_) resync();
}

void HscCounter::advance_to(uint64_t t) {
  if (!src_) return;
  const int64_t q1 = src_->quarter(t);
  if (q1 == q_) return;
  const int64_t k = q1 > q_ ? q1 - q_ : q_ - q1;
  const bool count = counting(pins_.levels()) && !blocked();
  if (count || dec_.has_memory()) {
    CountDecoder::Window w;
    window(src_->direction(), &w);
    if (count) {
      std::array<int, 4> first, seq;
      dec_.weights(w, &first, &seq);
      add_count(CountDecoder::sum(first, seq, k), false);  // matches inside the span are events of their own
    }
    dec_.skip(w, k);
  }
  q_ = q1;
  last_ = pins_at(q1, pins_.levels());
}

// First instant after now at which counting makes CV equal PV: the k-th boundary the
// source crosses, solved in O(1) from the 4-periodic weights.
uint64_t HscCounter::next_event_ns() {
  match_ = kNever;
  const int s = counter_source(n_);
  if (!src_ || src_->direction() == 0 || !ctx_.irq().present(s) || !ctx_.irq().enabled(s) ||
      !counting(pins_.levels()) || blocked())
    return match_;
  CountDecoder::Window w;
  window(src_->direction(), &w);
  std::array<int, 4> first, seq;
  dec_.weights(w, &first, &seq);
  match_ = first_match(first, seq, static_cast<int32_t>(pv() - cv()));
  return match_;
}

uint64_t HscCounter::first_match(const std::array<int, 4>& first, const std::array<int, 4>& seq, int64_t to_pv) const {
  const int dir = src_->direction();
  int64_t prefix = 0;
  for (int j = 1; j <= 4; ++j) {
    prefix += first[j - 1];
    if (first[j - 1] != 0 && prefix == to_pv) return src_->time_of_quarter(q_ + j * dir, ctx_.now());
  }
  // Past the first four boundaries: the k-th of the repeating ones, k counted from the fifth.
  const int64_t target = to_pv - prefix;
  prefix = 0;
  int64_t n = 0;
  for (int i = 0; i < 4; ++i) n += seq[i];
  int64_t best = -1;
  for (int j = 1; j <= 4; ++j) {
    prefix += seq[j - 1];
    if (seq[j - 1] == 0) continue;  // CV changes only where an edge counts
    const int64_t d = target - prefix;
    int64_t k = -1;
    if (n == 0) {
      if (d == 0) k = j;
    } else if (d % n == 0 && d / n >= 0) {
      k = 4 * (d / n) + j;
    }
    if (k > 0 && (best < 0 || k < best)) best = k;
  }
  if (best < 0) return kNever;
  return src_->time_of_quarter(q_ + (4 + best) * dir, ctx_.now());
}

void HscCounter::at(uint64_t t) {
  if (match_ == t) ctx_.match(counter_source(n_), n_, false, t);
}

// Edges at one instant act together: simultaneous U and D edges cancel.
void HscCounter::input_edges(uint64_t, const InputLevels& before, const InputLevels& after) {
  const Pins was = pins_at(q_, before);
  const bool was_counting = counting(before);
  const int d = dec_.step(was, pins_at(q_, after));
  if (was_counting && counting(after)) add_count(d, true);
  if (cleared(after)) set_cv(0);
}

void HscCounter::before_inputs() {
  hist_.push_back({ctx_.now(), total_});
  while (hist_.size() > 2 && hist_[1].first + window_ns_ <= ctx_.now()) hist_.pop_front();
}

// The software MASK/CLEAR/direction relays reach the counter at the I/O refresh.
void HscCounter::after_program() {
  sw_mask_ = ctx_.mem.bit(Area::M, mask_relay(n_));
  sw_clear_ = clear_relay(n_) >= 0 && ctx_.mem.bit(Area::M, clear_relay(n_));
  sw_dir_ = ctx_.mem.bit(Area::M, dir_relay(n_));
  if (cleared(pins_.levels())) set_cv(0);
}

void HscCounter::read_chip() { ctx_.set_reg32(cv_register(n_), cv_); }

void HscCounter::write_chip(bool pv) {
  if (pv) pv_ = ctx_.reg32(pv_register(n_));
  else cv_ = ctx_.reg32(cv_register(n_));
}

double HscCounter::frequency() const {
  if (hist_.size() < 2 || hist_.back().first == hist_.front().first) return 0.0;
  return double(hist_.back().second - hist_.front().second) * 1e9 / double(hist_.back().first - hist_.front().first);
}

}  // namespace hsc
}  // namespace plc_cell
