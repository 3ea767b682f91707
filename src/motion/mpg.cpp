// FUN148 MPG (docs/motion.md "FUN148").
#include "plc_cell/motion/mpg.h"

#include <algorithm>

#include "plc_cell/core/memory.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/motion/motion_unit.h"

namespace plc_cell {
namespace motion {

namespace {
constexpr uint32_t kHscCvReg = 4096;  // DR4096+2n: the CPU's copy of HSCn's CV
}

uint32_t Mpg::counter_value(int sc) const {
  if (hsc_) return static_cast<uint32_t>(hsc_->count(sc));
  return uint32_t(mem_.reg(Area::R, kHscCvReg + 2 * sc)) | (uint32_t(mem_.reg(Area::R, kHscCvReg + 2 * sc + 1)) << 16);
}

bool Mpg::fun148(const Fun148Call& c, uint64_t t) {
  if (c.sc < 0 || c.sc > 7 || c.ps < 0 || c.ps > 3) return false;
  State& s = st_[c.instance];
  advance(t);
  if (s.holding && s.ps != c.ps) release(s, c.instance);  // Ps changed: leave the old axis
  s.ps = c.ps;
  const uint32_t cv = counter_value(c.sc);
  // Wrap-safe 32-bit difference: the counter may roll over between two samples.
  const int64_t in = s.primed ? static_cast<int32_t>(cv - s.last_cv) : 0;
  s.primed = true;
  s.last_cv = cv;
  if (!c.en || c.fb == 0) {
    s.rem = 0;  // a disabled MPG only follows the counter: enabling it later sends nothing old
  } else if (in != 0) {
    const int64_t total = in * c.fa + s.rem;
    const int64_t pulses = total / c.fb;  // toward zero; the rest carries to the next sample
    s.rem = total - pulses * c.fb;
    if (pulses != 0) output(s, c, pulses, t);
  }
  // WR (AMBIG-27, inferred from the manual's Example E snapshot): WR+0 = 2 x Ps,
  // WR+1 = (EN << 8) | Ps, DWR+2 = the counter value of the last sample.
  const Address& w = c.wr;
  mem_.write({w.area, Width::Word, w.index}, static_cast<uint32_t>(2 * c.ps));
  mem_.write({w.area, Width::Word, w.index + 1}, (c.en ? 0x100u : 0u) | static_cast<uint32_t>(c.ps));
  mem_.write({w.area, Width::Word, w.index + 2}, cv & 0xFFFF);
  mem_.write({w.area, Width::Word, w.index + 3}, cv >> 16);
  return s.holding && unit_.axis(c.ps).moving();
}

void Mpg::output(State& s, const Fun148Call& c, int64_t pulses, uint64_t t) {
  const uint16_t lim = mem_.reg(Area::R, kLimitReg);
  if ((lim >> 8) == 0x55 && ((lim >> (2 * c.ps + (pulses > 0 ? 0 : 1))) & 1)) {
    s.rem = 0;  // travel limit: this direction is refused, the input is dropped
    return;
  }
  const uint32_t me = owner(c.instance);
  if (unit_.owner(c.ps) != UINT32_MAX && unit_.owner(c.ps) != me) return;  // held by FUN140/147/148
  Axis& ax = unit_.drive(c.ps);
  const AxisParams& par = unit_.params(c.ps);
  // A previous output still running is extended: its unsent pulses plus the new ones.
  int64_t pending = 0;
  double v = 0;
  if (s.holding && ax.moving()) {
    pending = ax.left_if_cut(t) * ax.direction();
    v = ax.frequency(t);
    ax.cut(t);
  } else if (ax.moving()) {
    return;  // still settling another user's move
  }
  const int64_t d = pending + pulses;
  if (d == 0) return release(s, c.instance);
  if (!s.holding) {
    unit_.take_axis(c.ps, me);
    s.holding = true;
  }
  const double fo = std::min(std::max(1.0, double(c.fo)), par.max_hz());
  const double f0 = std::min(par.start_hz(), fo);
  const double v_in = pending != 0 && (pending > 0) == (d > 0) ? v : f0;  // a reversal starts again from P5
  const Profile prof = Profile::plan(d < 0 ? -d : d, v_in, fo, f0, par.acc_hz_per_s(), par.dec_hz_per_s());
  ax.start(t, d, 0, (d > 0) != (par.p9_rot != 0), prof);
  unit_.set_rest(c.ps, 0);
}

void Mpg::psoff(int ps, uint64_t t) {
  advance(t);
  for (auto& kv : st_) {
    State& s = kv.second;
    if (!s.holding || s.ps != ps) continue;
    s.rem = 0;
    Axis& ax = unit_.drive(ps);
    const AxisParams& par = unit_.params(ps);
    if (mem_.bit(Area::M, kDecelRelay)) {
      ax.decelerate(t, par.start_hz(), par.dec_hz_per_s());
    } else {
      unit_.set_rest(ps, ax.left_if_cut(t));  // DR4072: what the cut left unsent
      ax.cut(t);
    }
    if (!ax.moving()) release(s, kv.first);
  }
}

void Mpg::release(State& s, uint32_t instance) {
  if (s.holding && s.ps >= 0) unit_.release_axis(s.ps, owner(instance));
  s.holding = false;
}

uint64_t Mpg::next_event_ns() const {
  uint64_t next = kNever;
  for (const auto& kv : st_)
    if (kv.second.holding) next = std::min(next, unit_.axis(kv.second.ps).end_ns());
  return next;
}

bool Mpg::holding() const {
  for (const auto& kv : st_)
    if (kv.second.holding) return true;
  return false;
}

void Mpg::advance(uint64_t t) {
  for (auto& kv : st_) {
    State& s = kv.second;
    if (!s.holding) continue;
    Axis& ax = unit_.drive(s.ps);
    const uint64_t end = ax.end_ns();
    if (ax.moving() && end <= t) ax.settle(end);
    if (!ax.moving()) release(s, kv.first);
  }
}

}  // namespace motion
}  // namespace plc_cell
