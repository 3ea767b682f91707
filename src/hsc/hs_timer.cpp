#include "plc_cell/hsc/hs_timer.h"

#include <algorithm>

#include "plc_cell/core/interrupt_sources.h"
#include "plc_cell/hsc/hsc_config.h"

namespace plc_cell {
namespace hsc {

uint64_t HsTimer::next_event_ns() {
  match_ = kNever;
  const int s = irq::kHsc0I + n_;
  if (!ctx_.irq().present(s) || !ctx_.irq().enabled(s)) return match_;
  uint64_t ticks = static_cast<uint32_t>(s_.pv - s_.cv0);
  if (ticks == 0) ticks = 1ull << 32;
  match_ = s_.base + ticks * kTimerTick;
  while (match_ <= ctx_.now()) match_ += (1ull << 32) * kTimerTick;
  return match_;
}

void HsTimer::at(uint64_t t) {
  if (match_ == t) ctx_.match(irq::kHsc0I + n_, n_, true, t);
}

void HsTimer::preset(uint32_t v) {
  s_.cv0 = v;
  s_.base = ctx_.now();
}

void HsTimer::read_chip() { ctx_.set_reg32(cv_register(n_), cv(ctx_.now())); }

void HsTimer::write_chip(bool pv) {
  if (pv) s_.pv = ctx_.reg32(pv_register(n_));
  else preset(ctx_.reg32(cv_register(n_)));
}

uint64_t HstaTimer::next_event_ns() {
  next_ = kNever;
  if (s_.pv == 0 || !ctx_.irq().present(irq::kHstaI) || !ctx_.irq().enabled(irq::kHstaI)) return next_;
  const uint64_t period = std::max<uint64_t>(s_.pv, 2) * kTimerTick;  // PV = 1 acts as 2 (AMBIG-12)
  next_ = s_.base + ((ctx_.now() - s_.base) / period + 1) * period;
  return next_;
}

void HstaTimer::at(uint64_t t) {
  if (next_ == t) ctx_.sched.raise(irq::kHstaI);
}

void HstaTimer::read_chip() {
  const uint64_t ticks = (ctx_.now() - s_.base) / kTimerTick;
  const uint32_t v = s_.pv == 0 ? s_.cv0 + static_cast<uint32_t>(ticks)
                                : static_cast<uint32_t>(ticks % std::max<uint64_t>(s_.pv, 2));
  ctx_.set_reg32(kHstaCv, v);
}

void HstaTimer::write_chip(bool pv) {
  if (pv) s_.pv = ctx_.mem.reg(Area::R, kHstaPv);
  else s_.cv0 = ctx_.reg32(kHstaCv);
  s_.base = ctx_.now();  // the timer starts over from the write
}

int TimeBaseInterrupt::active() const {
  const uint32_t mask = ctx_.mem.reg(Area::R, kTimeBaseMask);
  const uint32_t routines = static_cast<uint32_t>(ctx_.irq().present_mask() >> irq::kTimeBase0) & 0xFF;
  const uint32_t unmasked = routines & ~mask;
  return unmasked ? __builtin_ctz(unmasked) : -1;  // the smallest unmasked
}

uint64_t TimeBaseInterrupt::next_event_ns() {
  tb_ = active();
  next_ = kNever;
  if (tb_ >= 0) {
    const uint64_t p = uint64_t(irq::kTimeBaseMs[tb_]) * 1000000;
    next_ = run_ns_ + ((ctx_.now() - run_ns_) / p + 1) * p;
  }
  return next_;
}

void TimeBaseInterrupt::at(uint64_t t) {
  if (next_ == t) ctx_.sched.raise(irq::kTimeBase0 + tb_);
}

}  // namespace hsc
}  // namespace plc_cell
