// DRVZ, the zero return of a FUN140 step, stage by stage (docs/motion.md "Homing").
#include "plc_cell/motion/homing.h"

#include <algorithm>

#include "plc_cell/core/memory.h"
#include "plc_cell/motion/ramps.h"
#include "plc_cell/motion/switches.h"

namespace plc_cell {
namespace motion {

namespace {
constexpr uint64_t kMd1DelayNs = 500000000;  // MD1: 0.5 s on the DOG, then back out of it
constexpr uint64_t kClrPulseNs = 20000000;   // CLR on for 20 ms
}  // namespace

void Homing::run_endless(Program& p, uint64_t t, int sign, double hz) {
  AxisState& a = axes_[p.call.ps];
  const AxisParams& par = a.params;
  const Ramp rp = ramps_.of(p.call.ps);
  if (ramps_.step_form(p.call.ps)) hz = std::min(hz, rp.max);  // P6 creep too: pps is the limit
  double v_in = std::min(rp.start, hz);
  if (a.axis.moving()) {
    if (a.axis.direction() == sign) v_in = a.axis.frequency(t);  // change speed on the fly
    a.axis.cut(t);
  }
  const bool forward = (sign > 0) != (par.p9_rot != 0);
  const Profile prof = Profile::plan(-1, v_in, hz, rp.start, rp.acc, rp.dec);
  a.axis.start(t, sign, 0, forward, prof);
}

int Homing::start(Program& p, const Step& s, uint64_t t) {
  const AxisParams& par = axes_[p.call.ps].params;
  if (s.zero_mode < 0 || s.zero_mode > 2) return 50;
  if (par.dog_input() < 0 || par.dog_input() > 15) return 51;
  if (s.zero_mode == 2 && (par.pg0_input() < 0 || par.pg0_input() > 15)) return 52;
  if (par.clr_output() > 23) return 53;
  p.phase = Phase::Homing;
  p.home.stage = Home::Seek;  // reported below, once the start case is known
  p.home.until = kNever;
  p.home.pg0_count = 0;
  p.home.counting = false;
  p.home.dog_seen = false;
  p.t_cur = t;
  const int home_sign = par.p9_home ? -1 : 1;
  const bool on_dog = switches_.input(par.dog_input(), t) != par.dog_nc();
  if (on_dog && par.limit_input() >= 0) {
    // Started on the DOG: toward home to the limit first, then back through the DOG
    // (manual, zero return started at or in front of the DOG).
    set(p, Home::ToLimit, t);
    run_endless(p, t, home_sign, p.speed_hz);
  } else if (on_dog) {
    // On the DOG with no limit to go to: leave the DOG backward first, then the
    // normal sequence (docs/motion.md "Homing"; the manual needs the limit here).
    set(p, Home::Escape, t);
    p.home.dog_seen = true;
    run_endless(p, t, -home_sign, p.speed_hz);
  } else {
    set(p, Home::Seek, t);
    run_endless(p, t, home_sign, p.speed_hz);
  }
  return 0;
}

void Homing::set(Program& p, Home h, uint64_t t) {
  p.home.stage = h;
  static const char* const kNames[] = {"seek", "to_limit", "escape", "creep", "md1_stop", "md1_delay", "md1_back", "home"};
  for (auto& f : obs_) f(p.call.ps, kNames[static_cast<int>(h)], t);
}

uint64_t Homing::next_event(const Program& p) const {
  const AxisState& a = axes_[p.call.ps];
  if (p.home.stage == Home::Md1Delay || p.home.stage == Home::Clr) return p.home.until;
  if (p.home.stage == Home::Md1Stop) return a.axis.end_ns();
  if (!a.axis.moving()) return kNever;
  const AxisParams& par = a.params;
  const int dir = a.axis.direction();
  const int64_t pos = a.axis.position(p.t_cur);
  uint64_t next = kNever;
  for (const int x : {par.dog_input(), par.limit_input(), par.pg0_input()}) {
    if (x < 0) continue;
    for (const auto& sw : cfg_.axes[p.call.ps].switches) {
      if (sw.x != x) continue;
      const int64_t at = sw.next_change(pos, dir);
      if (at != INT64_MIN) next = std::min(next, a.axis.when_at(at));
    }
  }
  return next;
}

bool Homing::check(Program& p, uint64_t t) {
  AxisState& a = axes_[p.call.ps];
  const AxisParams& par = a.params;
  const Step& s = p.current();
  const int home_sign = par.p9_home ? -1 : 1;
  const bool dog = switches_.input(par.dog_input(), t) != par.dog_nc();
  const bool limit = par.limit_input() >= 0 && switches_.input(par.limit_input(), t) != par.limit_nc();
  const bool pg0 = par.pg0_input() >= 0 && switches_.input(par.pg0_input(), t);
  switch (p.home.stage) {
    case Home::Seek:
      return seek(p, s, t, dog, limit, pg0);
    case Home::ToLimit:  // started on the DOG: the DOG is ignored until the limit acts
      if (limit) {
        a.axis.cut(t);
        run_endless(p, t, -home_sign, p.speed_hz);
        set(p, Home::Escape, t);
        p.home.dog_seen = dog;
      }
      return false;
    case Home::Escape:
      if (dog) p.home.dog_seen = true;
      if (p.home.dog_seen && !dog) {
        a.axis.cut(t);
        run_endless(p, t, home_sign, p.speed_hz);
        set(p, Home::Seek, t);
      }
      return false;
    case Home::Creep:
      return creep(p, s, t, dog, pg0);
    case Home::Md1Stop:
      if (a.axis.moving() && t >= a.axis.end_ns()) a.axis.settle(t);
      if (!a.axis.moving() || t >= a.axis.end_ns()) {
        a.axis.settle(t);
        set(p, Home::Md1Delay, t);
        p.home.until = t + kMd1DelayNs;
      }
      return false;
    case Home::Md1Delay:
      if (t >= p.home.until) {
        p.home.until = kNever;
        run_endless(p, t, -home_sign, par.creep_hz());
        set(p, Home::Md1Back, t);
        if (!dog) return found(p, t);
      }
      return false;
    case Home::Md1Back:
      return !dog && found(p, t);
    case Home::Clr:
      return clear(p, t);
  }
  return false;
}

bool Homing::seek(Program& p, const Step& s, uint64_t t, bool dog, bool limit, bool pg0) {
  AxisState& a = axes_[p.call.ps];
  const AxisParams& par = a.params;
  const int home_sign = par.p9_home ? -1 : 1;
  if (dog) {
    if (s.zero_mode == 1) {  // MD1: slow down and stop on the DOG
      a.axis.decelerate(t, ramps_.of(p.call.ps).start, ramps_.of(p.call.ps).dec);
      set(p, Home::Md1Stop, t);
      if (!a.axis.moving()) {
        set(p, Home::Md1Delay, t);
        p.home.until = t + kMd1DelayNs;
      }
      return false;
    }
    run_endless(p, t, home_sign, par.creep_hz());
    set(p, Home::Creep, t);
    p.home.counting = s.zero_mode == 2 && !par.pg0_rear();
    p.home.prev_pg0 = pg0;
    p.home.pg0_count = 0;
    if (p.home.counting && par.p17_pg0 == 0) return found(p, t);
  } else if (limit) {  // in front of the DOG: back until the DOG has been passed
    a.axis.cut(t);
    run_endless(p, t, -home_sign, p.speed_hz);
    set(p, Home::Escape, t);
    p.home.dog_seen = false;
  }
  return false;
}

bool Homing::creep(Program& p, const Step& s, uint64_t t, bool dog, bool pg0) {
  const AxisParams& par = axes_[p.call.ps].params;
  HomeState& h = p.home;
  if (s.zero_mode == 0) return !dog && found(p, t);
  if (!h.counting && !dog) {  // MD2 rear edge: count from leaving the DOG
    h.counting = true;
    h.prev_pg0 = pg0;
    return par.p17_pg0 == 0 && found(p, t);
  }
  if (h.counting && pg0 && !h.prev_pg0 && ++h.pg0_count >= par.p17_pg0) return found(p, t);
  h.prev_pg0 = pg0;
  return false;
}

// The CLR pulse has ended: the home position is set.
bool Homing::clear(Program& p, uint64_t t) {
  AxisState& a = axes_[p.call.ps];
  const AxisParams& par = a.params;
  if (t < p.home.until) return false;
  // No CLR output (FFH): done at once; there is no Y to switch off.
  if (par.clr_output() >= 0) mem_.set_bit(Area::Y, par.clr_output(), false);
  p.home.until = kNever;
  a.axis.set_position(par.p16_zero);
  return true;
}

bool Homing::found(Program& p, uint64_t t) {
  AxisState& a = axes_[p.call.ps];
  a.axis.cut(t);
  set(p, Home::Clr, t);
  p.home.until = t;
  if (a.params.clr_output() >= 0) {
    mem_.set_bit(Area::Y, a.params.clr_output(), true);
    p.home.until = t + kClrPulseNs;  // then done
    return false;
  }
  return check(p, t);
}

}  // namespace motion
}  // namespace plc_cell
