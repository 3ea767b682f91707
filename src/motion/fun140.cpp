// FUN140 HSPSO at each scan: what EN, PAU and ABT ask of its program, and the inputs a
// move follows while it runs (R4056 = 5AH speed registers, EXT contacts).
#include <algorithm>

#include "plc_cell/core/memory.h"
#include "plc_cell/motion/homing.h"
#include "plc_cell/motion/positioning.h"
#include "plc_cell/motion/ramps.h"
#include "plc_cell/motion/status_registers.h"
#include "plc_cell/motion/switches.h"
#include "step_flow.h"

namespace plc_cell {
namespace motion {

using flow::kWrDn;

Fun140Outputs Positioning::fun140(const Fun140Call& c, uint64_t now_us) {
  const uint64_t t = now_us * 1000;
  if (c.ps < 0 || c.ps >= kAxes) return {};
  Program& p = programs_[c.instance];
  p.call = c;
  AxisState& a = x_.axes[c.ps];
  advance(p, t);
  if (!p.external) {
    const uint16_t wr1 = x_.mem.read({c.wr.area, Width::Word, c.wr.index + 1});
    if (!(wr1 & kWrDn)) p.dn = false;  // the user cleared WR+1 (DN off)
  }
  p.t_cur = t;
  const bool active = p.phase == Phase::Moving || p.phase == Phase::Waiting || p.phase == Phase::SpeedWait ||
                      p.phase == Phase::Paused || p.phase == Phase::Stopping || p.phase == Phase::Homing;
  if (c.abt) {
    if (active && p.phase != Phase::Stopping) stop(p, t, Phase::Idle);
    p.step = 0;
    if (!p.external) x_.mem.write({c.wr.area, Width::Word, c.wr.index}, 0);
  } else if (!c.en) {
    if (active && p.phase != Phase::Stopping) stop(p, t, Phase::Idle);
  } else if (p.phase == Phase::Idle || p.phase == Phase::Done) {
    enable(p, c, t);
  } else if (c.pau && !p.prev_pau && p.phase == Phase::Moving) {
    stop(p, t, Phase::Paused);
  } else if (!c.pau && p.phase == Phase::Paused) {
    resume(p, c, t);
  } else if (p.phase == Phase::Homing) {
    home_check(p, t);  // inputs that no axis position drives are seen at the scans
    advance(p, t);
  } else if (p.phase == Phase::SpeedWait) {
    start_move(p, p.current(), t);
  } else if (p.phase == Phase::Moving && !c.pau) {
    follow(p, c, t);
  } else if (p.phase == Phase::Waiting && p.wait_until == kNever) {
    if (flow::contact(x_.mem, p.current())) {
      go_to(p, -1, t);
      advance(p, t);
    }
  }
  if (!c.en) p.armed = true;
  p.prev_en = c.en;
  p.prev_pau = c.pau;
  p.prev_abt = c.abt;
  write_wr(p);
  x_.status.write(t);
  x_.switches.write(t);
  Fun140Outputs o;
  o.act = a.owner == c.instance && a.axis.moving();
  o.err = p.err;
  o.dn = p.dn;
  return o;
}

// EN = 1: start at the next step once the axis is free (and EN was off since the last run).
void Positioning::enable(Program& p, const Fun140Call& c, uint64_t t) {
  AxisState& a = x_.axes[c.ps];
  if (!p.armed || (a.owner != kFree && a.owner != c.instance) || a.axis.moving()) return;
  p.armed = false;
  p.err = false;
  a.finished = false;
  if (!load(p)) return;
  a.owner = c.instance;
  const int n = static_cast<int>(p.table.steps.size());
  const int cur = p.external ? p.step : static_cast<int16_t>(x_.mem.read({c.wr.area, Width::Word, c.wr.index}));
  p.chain = false;
  start_step(p, cur <= 0 || cur >= n ? 1 : cur + 1, t);
  advance(p, t);
}

// Resumes the unfinished output from standstill.
void Positioning::resume(Program& p, const Fun140Call& c, uint64_t t) {
  AxisState& a = x_.axes[c.ps];
  const Ramp rp = x_.ramps.of(c.ps);
  const int64_t n = p.endless ? -1 : p.paused_left;
  if (n == 0) {
    x_.ramps.set_done(c.ps, true);
    step_done(p, t);
    transfer(p, t);
    return;
  }
  const Profile prof = Profile::plan(n, std::min(rp.start, p.speed_hz), p.speed_hz, rp.start, rp.acc, rp.dec);
  x_.ramps.set_done(c.ps, false);
  a.axis.start(t, p.endless ? p.move_delta_sign : p.move_delta_sign * n, 0, p.move_forward, prof);
  p.phase = Phase::Moving;
}

void Positioning::follow(Program& p, const Fun140Call& c, uint64_t t) {
  AxisState& a = x_.axes[c.ps];
  const Step& s = p.current();
  if ((x_.mem.reg(Area::R, kDynamicReg) & 0xFF) == 0x5A && s.speed.kind != Operand::Const &&
      s.motion != Motion::Drvz && !x_.ramps.step_form(c.ps)) {
    // R4056 low byte 5AH: the speed register is followed during the output.
    const int64_t v = flow::read32(x_.mem, s.speed.kind, s.speed.value);
    const double hz = std::min(a.params.speed_hz(v), a.params.max_hz());
    if (v > 0 && hz >= 1 && hz <= kMaxHz && hz != p.speed_hz) {
      p.speed_hz = hz;
      const double v_out = s.motion == Motion::Drvc ? hz : a.params.start_hz();
      a.axis.retarget(t, hz, v_out, a.params.acc_hz_per_s(), a.params.dec_hz_per_s());
      if (s.motion == Motion::Drvc) p.chain_speed = a.axis.profile().end_speed();
    }
  }
  if (s.transfer == Transfer::Ext && flow::contact(x_.mem, s)) {  // EXT: cut the move short, go on now
    p.paused_left = a.axis.left_if_cut(t);
    a.rest = p.paused_left;
    a.axis.cut(t);
    step_done(p, t);
    x_.status.write(t);  // DR4072 holds the rest for the next step (manual example 1)
    go_to(p, -1, t);
    advance(p, t);
  }
}

void Positioning::run_unit_programs(uint64_t now_us) {
  for (auto& kv : programs_)
    if (kv.second.external) fun140(kv.second.call, now_us);
}

void Positioning::psoff(int ps, uint64_t t) {
  for (auto& kv : programs_) {
    Program& p = kv.second;
    if (p.call.ps != ps) continue;
    advance(p, t);
    if (p.phase == Phase::Moving || p.phase == Phase::Waiting || p.phase == Phase::SpeedWait || p.phase == Phase::Paused)
      stop(p, t, Phase::Idle);
  }
}

int Positioning::step(int ps) const {
  for (const auto& kv : programs_)
    if (kv.second.call.ps == ps && x_.axes[ps].owner == kv.first) return kv.second.step;
  return 0;
}

}  // namespace motion
}  // namespace plc_cell
