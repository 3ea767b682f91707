// The FUN140 program state machine: steps, transfers, stops and errors, in virtual time.
#include "plc_cell/motion/positioning.h"

#include <algorithm>

#include "plc_cell/core/memory.h"
#include "plc_cell/motion/homing.h"
#include "plc_cell/motion/move_plan.h"
#include "plc_cell/motion/ramps.h"
#include "plc_cell/motion/status_registers.h"
#include "plc_cell/timeline/scheduler.h"
#include "step_flow.h"

namespace plc_cell {
namespace motion {

namespace {
using flow::kTimeUnitNs;
using flow::kMaxStepsPerInstant;
using flow::kWrPaused;
using flow::kWrWaiting;
using flow::kWrEndless;
using flow::kWrAct;
using flow::kWrErr;
using flow::kWrDn;
}  // namespace

uint64_t Positioning::next_event(const Program& p) const {
  const Axis& ax = x_.axes[p.call.ps].axis;
  uint64_t next = kNever;
  if (p.phase == Phase::Moving || p.phase == Phase::Stopping) next = ax.end_ns();
  if (p.phase == Phase::Moving && p.act_deadline < next) next = p.act_deadline;
  if (p.phase == Phase::Waiting) next = p.wait_until;
  if (p.phase == Phase::Homing) next = x_.homing.next_event(p);
  return next;
}

uint64_t Positioning::next_event_ns() const {
  uint64_t next = kNever;
  for (const auto& kv : programs_) next = std::min(next, next_event(kv.second));
  return next;
}

void Positioning::advance(uint64_t t) {
  for (auto& kv : programs_) advance(kv.second, t);
}

void Positioning::advance(Program& p, uint64_t t) {
  AxisState& a = x_.axes[p.call.ps];
  Axis& ax = a.axis;
  for (int guard = 0; guard < kMaxStepsPerInstant; ++guard) {
    const uint64_t next = next_event(p);
    const bool act_first = p.phase == Phase::Moving && next == p.act_deadline && next < ax.end_ns();
    if (next == kNever || next > t) return;
    p.t_cur = next;
    if (p.phase == Phase::Homing) {
      home_check(p, next);
    } else if (act_first) {  // ACT: the time is up, go on even if the output is not finished
      p.paused_left = ax.left_if_cut(next);
      a.rest = p.paused_left;
      ax.cut(next);
      step_done(p, next);
      go_to(p, -1, next);
    } else if (p.phase == Phase::Moving) {
      ax.settle(next);
      finish_step(p, next);
    } else if (p.phase == Phase::Stopping) {
      p.paused_left = ax.remaining(next);
      a.rest = p.paused_left;
      ax.settle(next);
      p.phase = p.after_stop;
      if (p.phase != Phase::Paused) a.owner = kFree;
    } else {  // Waiting: WAIT Time, or the ACT time after an early end
      go_to(p, -1, next);
    }
  }
  fail(p, 34, t);  // a GOTO loop of empty steps
}

void Positioning::finish_step(Program& p, uint64_t t) {
  p.paused_left = 0;
  x_.axes[p.call.ps].rest = 0;
  x_.ramps.set_done(p.call.ps, true);  // before the step's observers and PSOnI look
  step_done(p, t);
  transfer(p, t);
}

void Positioning::home_check(Program& p, uint64_t t) {
  if (!x_.homing.check(p, t)) return;
  p.phase = Phase::Moving;  // for the step bookkeeping
  finish_step(p, t);
}

void Positioning::step_done(Program& p, uint64_t t) {
  p.dn = true;
  x_.mem.set_reg(Area::R, kStepReg + p.call.ps, static_cast<uint16_t>(p.step));
  write_wr(p);
  for (auto& f : step_obs_) f(p.call.ps, p.step, t);
  x_.sched.raise(irq::kPso0I + p.call.ps);  // in the scheduler's loop: dispatched with the instant's others
}

void Positioning::transfer(Program& p, uint64_t t) {
  const Step& s = p.current();
  switch (s.transfer) {
    case Transfer::None:
      return go_to(p, -1, t);
    case Transfer::WaitTime:
      p.phase = Phase::Waiting;
      p.wait_until = t + uint64_t(read_time(s)) * kTimeUnitNs;
      return;
    case Transfer::Act:
      if (p.act_deadline != kNever && p.act_deadline > t) {
        p.phase = Phase::Waiting;
        p.wait_until = p.act_deadline;
        return;
      }
      return go_to(p, -1, t);
    case Transfer::WaitContact:
    case Transfer::Ext:
      if (flow::contact(x_.mem, s)) return go_to(p, -1, t);
      p.phase = Phase::Waiting;
      p.wait_until = kNever;  // the contact is looked at every scan
      return;
  }
}

uint16_t Positioning::read_time(const Step& s) const { return flow::time16(x_.mem, s); }

void Positioning::go_to(Program& p, int target, uint64_t t) {
  const Step& s = p.current();
  const int n = static_cast<int>(p.table.steps.size());
  if (target < 0 && (target = flow::goto_target(x_.mem, s, p.step, n)) == 0) return fail(p, 34, t);
  if (target > n) {  // past the last step: the program is finished
    p.phase = Phase::Done;
    p.chain = false;
    x_.axes[p.call.ps].finished = true;
    x_.axes[p.call.ps].owner = kFree;
    return;
  }
  start_step(p, target, t);
}

void Positioning::start_step(Program& p, int k, uint64_t t) {
  p.step = k;
  p.wait_until = kNever;
  if (!p.external) x_.mem.write({p.call.wr.area, Width::Word, p.call.wr.index}, static_cast<uint16_t>(k));
  const Step& s = p.table.steps[k - 1];
  p.act_deadline = s.transfer == Transfer::Act ? t + uint64_t(read_time(s)) * kTimeUnitNs : kNever;
  start_move(p, s, t);
}

void Positioning::start_move(Program& p, const Step& s, uint64_t t) {
  const int ps = p.call.ps;
  AxisState& a = x_.axes[ps];
  const Ramp rp = x_.ramps.of(ps);
  if (x_.ramps.step_form(ps)) {
    p.speed_hz = rp.max;  // the step form has one speed (STEPMOVE takes none): SPD is not read
  } else {
    const int64_t v = flow::value32(x_.mem, s.speed);
    if (v == 0) {  // SPD 0: wait until the speed register becomes non-zero
      p.phase = Phase::SpeedWait;
      return;
    }
    const double hz = a.params.speed_hz(v);
    if (v < 0 || hz > kMaxHz || hz < 1) return fail(p, 31, t);
    p.speed_hz = std::min(hz, rp.max);
  }
  if (s.motion == Motion::Drvz) {
    x_.ramps.set_done(ps, false);
    if (const int code = x_.homing.start(p, s, t)) return fail(p, code, t);
    return home_check(p, t);  // starting on the limit
  }
  StepMove m;
  const int64_t stroke = flow::value32(x_.mem, s.stroke);
  if (const int code = plan_step_move(s, stroke, a.params, a.axis.position(t), p.chain, p.chain_forward, &m))
    return fail(p, code, t);
  p.endless = m.endless;
  if (!m.endless && (m.delta == 0 || m.pulses <= 0)) {  // already there: the step completes at once
    if (p.empty_at != t) p.empty_at = t, p.empty_steps = 0;
    if (++p.empty_steps > static_cast<int>(p.table.steps.size())) return fail(p, 34, t);  // a GOTO loop of empty steps
    p.chain = false;
    return finish_step(p, t);  // the done relay cleared and set at once: all of its no pulses are sent
  }
  const Profile prof = step_profile(m, rp, p.speed_hz, p.chain, p.chain_speed, s.motion == Motion::Drvc);
  x_.ramps.set_done(ps, false);
  a.axis.start(t, m.delta, m.endless ? 0 : m.comp, m.forward, prof);
  p.phase = Phase::Moving;
  p.move_forward = m.forward;
  p.move_delta_sign = m.delta < 0 ? -1 : 1;
  p.chain = s.motion == Motion::Drvc;
  p.chain_forward = m.forward;
  p.chain_speed = prof.end_speed();
}

void Positioning::stop(Program& p, uint64_t t, Phase then, bool force_decel) {
  AxisState& a = x_.axes[p.call.ps];
  Axis& ax = a.axis;
  p.chain = false;
  if (ax.moving() && (p.phase == Phase::Moving || p.phase == Phase::Homing)) {
    if (force_decel || x_.mem.bit(Area::M, kDecelRelay)) {
      const Ramp rp = x_.ramps.of(p.call.ps);
      ax.decelerate(t, rp.start, rp.dec);
      if (ax.moving()) {
        p.phase = Phase::Stopping;
        p.after_stop = then;
        return;
      }
    } else {
      p.paused_left = ax.left_if_cut(t);
      a.rest = p.paused_left;
      ax.cut(t);
    }
  }
  p.phase = then;
  if (then != Phase::Paused) a.owner = kFree;
}

void Positioning::fail(Program& p, int code, uint64_t t) {
  x_.axes[p.call.ps].axis.cut(t);
  p.phase = Phase::Idle;
  p.chain = false;
  p.err = true;
  x_.axes[p.call.ps].owner = kFree;
  x_.mem.set_reg(Area::R, kErrReg + p.call.ps, static_cast<uint16_t>(code));
  write_wr(p);
}

bool Positioning::load(Program& p) {
  if (p.external) return !p.table.steps.empty();
  const Address& sr = p.call.sr;
  const size_t avail = Memory::word_count(sr.area) - sr.index;
  TableError e;
  Table t;
  if (!decode_table(x_.mem.words(sr.area) + sr.index, avail, &t, &e)) {
    p.table = {};
    fail(p, e.code, x_.now_ns);
    return false;
  }
  p.table = std::move(t);
  return true;
}

void Positioning::write_wr(Program& p) {
  if (p.external) return;
  const Address wr1{p.call.wr.area, Width::Word, p.call.wr.index + 1};
  uint16_t w = static_cast<uint16_t>(p.table.steps.size() & 0xFF);
  if (p.phase == Phase::Paused) w |= kWrPaused;
  if (Homing::waiting(p)) w |= kWrWaiting;
  if (p.phase == Phase::Waiting) w |= kWrWaiting;
  if (p.endless && (p.phase == Phase::Moving || p.phase == Phase::Paused)) w |= kWrEndless;
  if (x_.axes[p.call.ps].axis.moving() && x_.axes[p.call.ps].owner == p.call.instance) w |= kWrAct;
  if (p.err) w |= kWrErr;
  if (p.dn) w |= kWrDn;
  x_.mem.write(wr1, w);
}

}  // namespace motion
}  // namespace plc_cell
