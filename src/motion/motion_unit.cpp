// FUN140 positioning programs on the PSO axes, in virtual time (docs/motion.md).
#include "plc_cell/motion/motion_unit.h"

#include <algorithm>
#include <cmath>

#include "plc_cell/core/memory.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/motion/interpolation.h"
#include "plc_cell/motion/mpg.h"
#include "step_flow.h"

namespace plc_cell {
namespace motion {

namespace {
ScanEngine& engine_of(Plc& p) { return *p.locked([](ScanEngine& e, Memory&) { return &e; }); }
Memory& memory_of(Plc& p) { return *p.locked([](ScanEngine&, Memory& m) { return &m; }); }

constexpr uint32_t kReadyRelay = 1992;  // M1992+n: axis ready
constexpr uint32_t kLastStepRelay = 1996;  // M1996+n: last step finished
constexpr uint32_t kDynamicReg = 4056;  // low byte 5AH: SPD registers followed during the output
constexpr uint32_t kErrReg = 4060, kStepReg = 4064, kRemainReg = 4072, kFreqReg = 4080, kPosReg = 4088;
constexpr uint64_t kTimeUnitNs = 10000000;  // WAIT/ACT times are in 0.01 s
constexpr int kMaxStepsPerInstant = 1000;
constexpr uint32_t kExternal = 0x80000000u;  // instance ids of unit-run programs (+ axis)   // GOTO loops of empty moves must not hang a scan

constexpr uint16_t kWrPaused = 1u << 8, kWrWaiting = 1u << 9, kWrEndless = 1u << 10, kWrAct = 1u << 12,
                   kWrErr = 1u << 13, kWrDn = 1u << 14;
}  // namespace

MotionUnit::MotionUnit(Plc& plc)
    : plc_(plc),
      engine_(engine_of(plc)),
      mem_(memory_of(plc)),
      sched_(*plc.locked([](ScanEngine& e, Memory&) { return &timeline::Scheduler::of(e); })) {
  plc_.locked([this](ScanEngine& e, Memory&) {
    e.add_hook(this);
    hsc_ = hsc::HscUnit::of(&e);
    sched_.add_source(this);
  });
  interp_ = std::make_unique<Interpolation>(*this, mem_);
  mpg_ = std::make_unique<Mpg>(*this, mem_, hsc_);
}

MotionUnit::~MotionUnit() {
  plc_.locked([this](ScanEngine& e, Memory&) {
    if (hsc_ && hsc::HscUnit::of(&e) == hsc_) detach_signals();
    sched_.remove_source(this);
    e.remove_hook(this);
  });
}

uint64_t MotionUnit::next_event(const Program& p) const {
  const Axis& ax = axes_[p.call.ps].axis;
  uint64_t next = kNever;
  if (p.phase == Phase::Moving || p.phase == Phase::Stopping) next = ax.end_ns();
  if (p.phase == Phase::Moving && p.act_deadline < next) next = p.act_deadline;
  if (p.phase == Phase::Waiting) next = p.wait_until;
  if (p.phase == Phase::Homing) next = home_next_event(p);
  return next;
}

uint64_t MotionUnit::next_event_ns() {
  uint64_t next = kNever;
  for (const auto& kv : programs_) next = std::min(next, next_event(kv.second));
  return std::min({next, interp_->next_event_ns(), mpg_->next_event_ns()});
}

void MotionUnit::at(uint64_t t) {
  if (next_event_ns() > t) return;  // another subsystem's instant
  adopt_ladder_positions();
  advance(t);
  write_status(t);  // the routines of this instant read its position, frequency, ...
}

MotionUnit* MotionUnit::of(ScanEngine* engine) { return engine ? engine->extensions().get<MotionUnit>() : nullptr; }

void MotionUnit::attached(ScanEngine& e) { e.extensions().attach(this); }
void MotionUnit::detached(ScanEngine& e) { e.extensions().detach(this); }

// ---- memory helpers -------------------------------------------------------------

int32_t MotionUnit::read32(Operand::Kind k, int32_t i) const { return flow::read32(mem_, k, i); }

uint16_t MotionUnit::read16(Operand::Kind k, int32_t i) const { return mem_.reg(flow::area(k), i); }

bool MotionUnit::contact(const Step& s) const { return flow::contact(mem_, s); }

// ---- scan hook ------------------------------------------------------------------

void MotionUnit::before_program(uint64_t now_us) {
  const uint64_t t = now_us * 1000;
  if (!preloaded_) preload();
  adopt_ladder_positions();
  advance(t);
  for (auto& kv : programs_)
    if (kv.second.external) fun140(kv.second.call, now_us);
  write_status(t);
  write_switches(t);
}

void MotionUnit::adopt_ladder_positions() {
  // A ladder write of DR4088 on an idle axis sets its position (homing by ladder).
  for (int n = 0; n < kAxes; ++n) {
    AxisState& a = axes_[n];
    const int64_t reg = static_cast<int32_t>(uint32_t(mem_.reg(Area::R, kPosReg + 2 * n)) |
                                             (uint32_t(mem_.reg(Area::R, kPosReg + 2 * n + 1)) << 16));
    if (reg != a.written_pos && !a.axis.moving()) a.axis.set_position(reg);
  }
}

void MotionUnit::after_program(uint64_t now_us) { write_status(now_us * 1000); }

void MotionUnit::preload() {
  // The cell YAML's tables and parameter tables, as an MMI would write them at RUN.
  preloaded_ = true;
  for (int n = 0; n < kAxes; ++n) {
    const AxisDef& a = cfg_.axes[n];
    const auto put = [&](const Address& at, const uint16_t* w, size_t count) {
      for (size_t i = 0; i < count && at.index + i < Memory::word_count(at.area); ++i)
        mem_.set_reg(at.area, static_cast<uint32_t>(at.index + i), w[i]);
    };
    if (a.has_table) {
      const std::vector<uint16_t> r = encode_table(a.table);
      put(a.table_at, r.data(), r.size());
    }
    if (a.params_image) {
      uint16_t r[kParamWords];
      a.params.to_registers(r);
      put(a.params_at, r, kParamWords);
    }
  }
  for (const auto& g : cfg_.groups)  // FUN147 tables (axes: gp0/gp1)
    if (g.has_table) {
      const std::vector<uint16_t> r = encode_lin_table(g.table);
      for (size_t i = 0; i < r.size() && g.table_at.index + i < Memory::word_count(g.table_at.area); ++i)
        mem_.set_reg(g.table_at.area, static_cast<uint32_t>(g.table_at.index + i), r[i]);
    }
}

void MotionUnit::on_stop() {
  preloaded_ = false;
  for (auto& a : axes_) {
    a.axis.cut(now_ns_);
    a.owner = UINT32_MAX;
  }
  programs_.clear();
  interp_->on_stop();
  mpg_->on_stop();
}

void MotionUnit::advance(uint64_t t) {
  for (auto& kv : programs_) advance(kv.second, t);
  interp_->advance(t);  // FUN147 groups and FUN148 outputs on the same clock
  mpg_->advance(t);
  now_ns_ = std::max(now_ns_, t);
}

// ---- the program state machine ----------------------------------------------------

void MotionUnit::advance(Program& p, uint64_t t) {
  Axis& ax = axes_[p.call.ps].axis;
  for (int guard = 0; guard < kMaxStepsPerInstant; ++guard) {
    const uint64_t next = next_event(p);
    const bool act_first = p.phase == Phase::Moving && next == p.act_deadline && next < ax.end_ns();
    if (next == kNever || next > t) return;
    p.t_cur = next;
    if (p.phase == Phase::Homing) {
      home_check(p, next);
    } else if (act_first) {  // ACT: the time is up, go on even if the output is not finished
      p.paused_left = ax.left_if_cut(next);
      axes_[p.call.ps].rest = p.paused_left;
      ax.cut(next);
      step_done(p, next);
      go_to(p, -1, next);
    } else if (p.phase == Phase::Moving) {
      ax.settle(next);
      p.paused_left = 0;
      axes_[p.call.ps].rest = 0;
      set_done(p.call.ps, true);  // before the step's observers and PSOnI look
      step_done(p, next);
      transfer(p, next);
    } else if (p.phase == Phase::Stopping) {
      p.paused_left = ax.remaining(next);
      axes_[p.call.ps].rest = p.paused_left;
      ax.settle(next);
      p.phase = p.after_stop;
      if (p.phase != Phase::Paused) axes_[p.call.ps].owner = UINT32_MAX;
    } else {  // Waiting: WAIT Time, or the ACT time after an early end
      go_to(p, -1, next);
    }
  }
  fail(p, 34, t);  // a GOTO loop of empty steps
}

void MotionUnit::step_done(Program& p, uint64_t t) {
  p.dn = true;
  mem_.set_reg(Area::R, kStepReg + p.call.ps, static_cast<uint16_t>(p.step));
  write_wr(p);
  for (auto& f : step_obs_) f(p.call.ps, p.step, t);
  sched_.raise(irq::kPso0I + p.call.ps);  // in the scheduler's loop: dispatched with the instant's others
}

void MotionUnit::transfer(Program& p, uint64_t t) {
  const Step& s = p.table.steps[p.step - 1];
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
      if (contact(s)) return go_to(p, -1, t);
      p.phase = Phase::Waiting;
      p.wait_until = kNever;  // the contact is looked at every scan
      return;
  }
}

uint16_t MotionUnit::read_time(const Step& s) const { return flow::time16(mem_, s); }

void MotionUnit::go_to(Program& p, int target, uint64_t t) {
  const Step& s = p.table.steps[p.step - 1];
  const int n = static_cast<int>(p.table.steps.size());
  if (target < 0 && (target = flow::goto_target(mem_, s, p.step, n)) == 0) return fail(p, 34, t);
  if (target > n) {  // past the last step: the program is finished
    p.phase = Phase::Done;
    p.chain = false;
    axes_[p.call.ps].finished = true;
    axes_[p.call.ps].owner = UINT32_MAX;
    return;
  }
  start_step(p, target, t);
}

void MotionUnit::start_step(Program& p, int k, uint64_t t) {
  p.step = k;
  p.wait_until = kNever;
  if (!p.external) mem_.write({p.call.wr.area, Width::Word, p.call.wr.index}, static_cast<uint16_t>(k));
  const Step& s = p.table.steps[k - 1];
  p.act_deadline = s.transfer == Transfer::Act ? t + uint64_t(read_time(s)) * kTimeUnitNs : kNever;
  start_move(p, s, t);
}

void MotionUnit::start_move(Program& p, const Step& s, uint64_t t) {
  AxisState& a = axes_[p.call.ps];
  const AxisParams& par = a.params;
  const Ramp rp = ramp(p.call.ps);
  if (cfg_.axes[p.call.ps].stepspeed.used) {
    p.speed_hz = rp.max;  // the step form has one speed (STEPMOVE takes none): SPD is not read
  } else {
    const int64_t v = s.speed.kind == Operand::Const ? s.speed.value : read32(s.speed.kind, s.speed.value);
    if (v == 0) {  // SPD 0: wait until the speed register becomes non-zero
      p.phase = Phase::SpeedWait;
      return;
    }
    const double hz = par.speed_hz(v);
    if (v < 0 || hz > kMaxHz || hz < 1) return fail(p, 31, t);
    p.speed_hz = std::min(hz, rp.max);
  }
  if (s.motion == Motion::Drvz) {
    set_done(p.call.ps, false);
    return start_homing(p, s, t);
  }

  const int64_t stroke = s.stroke.kind == Operand::Const ? s.stroke.value : read32(s.stroke.kind, s.stroke.value);
  if (stroke < -99999999 || stroke > 99999999) return fail(p, 33, t);
  const int64_t pulses = s.ut ? par.ut_to_pulses(stroke) : stroke;
  const bool rot = par.p9_rot != 0;
  int64_t delta;  // change of the logical position
  bool forward;
  bool endless = false;
  if (s.abs) {
    delta = pulses - a.axis.position(t);
    forward = (delta > 0) != rot;
  } else {
    endless = pulses == 0;
    forward = s.dir > 0 || (s.dir == 0 && pulses >= 0);
    if (p.chain) forward = p.chain_forward;
    const int64_t len = pulses < 0 ? -pulses : pulses;
    delta = forward != rot ? len : -len;
    if (endless) delta = forward != rot ? 1 : -1;  // the direction only
  }
  if (std::llabs(delta) > 2147483647LL) return fail(p, 40, t);
  const int64_t comp = forward ? par.p10_fwd_comp : int64_t(par.p7_backlash) + par.p11_bwd_comp;
  const int64_t n = endless ? -1 : std::llabs(delta) + comp;
  p.endless = endless;
  if (!endless && (delta == 0 || n <= 0)) {  // already there: the step completes at once
    if (p.empty_at != t) p.empty_at = t, p.empty_steps = 0;
    if (++p.empty_steps > static_cast<int>(p.table.steps.size())) return fail(p, 34, t);  // a GOTO loop of empty steps
    p.chain = false;
    p.paused_left = 0;
    a.rest = 0;
    set_done(p.call.ps, true);  // cleared and set at once: all of its no pulses are sent
    step_done(p, t);
    return transfer(p, t);
  }
  const double f0 = rp.start;
  const double v_in = p.chain ? std::min(p.chain_speed, std::max(p.speed_hz, p.chain_speed)) : std::min(f0, p.speed_hz);
  const double v_out = s.motion == Motion::Drvc ? p.speed_hz : f0;
  const Profile prof = Profile::plan(n, v_in, p.speed_hz, v_out, rp.acc, rp.dec);
  set_done(p.call.ps, false);
  a.axis.start(t, delta, endless ? 0 : comp, forward, prof);
  p.phase = Phase::Moving;
  p.move_forward = forward;
  p.move_delta_sign = delta < 0 ? -1 : 1;
  p.chain = s.motion == Motion::Drvc;
  p.chain_forward = forward;
  p.chain_speed = prof.end_speed();
}

void MotionUnit::stop(Program& p, uint64_t t, Phase then, bool force_decel) {
  Axis& ax = axes_[p.call.ps].axis;
  p.chain = false;
  if (ax.moving() && (p.phase == Phase::Moving || p.phase == Phase::Homing)) {
    if (force_decel || mem_.bit(Area::M, kDecelRelay)) {
      const Ramp rp = ramp(p.call.ps);
      ax.decelerate(t, rp.start, rp.dec);
      if (ax.moving()) {
        p.phase = Phase::Stopping;
        p.after_stop = then;
        return;
      }
    } else {
      p.paused_left = ax.left_if_cut(t);
      axes_[p.call.ps].rest = p.paused_left;
      ax.cut(t);
    }
  }
  p.phase = then;
  if (then != Phase::Paused) axes_[p.call.ps].owner = UINT32_MAX;
}

void MotionUnit::fail(Program& p, int code, uint64_t t) {
  axes_[p.call.ps].axis.cut(t);
  p.phase = Phase::Idle;
  p.chain = false;
  p.err = true;
  axes_[p.call.ps].owner = UINT32_MAX;
  mem_.set_reg(Area::R, kErrReg + p.call.ps, static_cast<uint16_t>(code));
  write_wr(p);
}

bool MotionUnit::load(Program& p) {
  if (p.external) return !p.table.steps.empty();
  const Address& sr = p.call.sr;
  const size_t avail = Memory::word_count(sr.area) - sr.index;
  TableError e;
  Table t;
  if (!decode_table(mem_.words(sr.area) + sr.index, avail, &t, &e)) {
    p.table = {};
    fail(p, e.code, now_ns_);
    return false;
  }
  p.table = std::move(t);
  return true;
}

Fun140Outputs MotionUnit::fun140(const Fun140Call& c, uint64_t now_us) {
  const uint64_t t = now_us * 1000;
  if (c.ps < 0 || c.ps >= kAxes) return {};
  Program& p = programs_[c.instance];
  p.call = c;
  AxisState& a = axes_[c.ps];
  advance(p, t);
  if (!p.external) {
    const uint16_t wr1 = mem_.read({c.wr.area, Width::Word, c.wr.index + 1});
    if (!(wr1 & kWrDn)) p.dn = false;  // the user cleared WR+1 (DN off)
  }
  p.t_cur = t;
  const bool active = p.phase == Phase::Moving || p.phase == Phase::Waiting || p.phase == Phase::SpeedWait ||
                      p.phase == Phase::Paused || p.phase == Phase::Stopping || p.phase == Phase::Homing;
  if (c.abt) {
    if (active && p.phase != Phase::Stopping) stop(p, t, Phase::Idle);
    p.step = 0;
    if (!p.external) mem_.write({c.wr.area, Width::Word, c.wr.index}, 0);
  } else if (!c.en) {
    if (active && p.phase != Phase::Stopping) stop(p, t, Phase::Idle);
  } else if (p.phase == Phase::Idle || p.phase == Phase::Done) {
    // EN = 1: start at the next step once the axis is free (and EN was off since the last run).
    if (p.armed && (a.owner == UINT32_MAX || a.owner == c.instance) && !a.axis.moving()) {
      p.armed = false;
      p.err = false;
      a.finished = false;
      if (load(p)) {
        a.owner = c.instance;
        const int n = static_cast<int>(p.table.steps.size());
        const int cur = p.external ? p.step : static_cast<int16_t>(mem_.read({c.wr.area, Width::Word, c.wr.index}));
        p.chain = false;
        start_step(p, cur <= 0 || cur >= n ? 1 : cur + 1, t);
        advance(p, t);
      }
    }
  } else if (c.pau && !p.prev_pau && p.phase == Phase::Moving) {
    stop(p, t, Phase::Paused);
  } else if (!c.pau && p.phase == Phase::Paused) {
    // Resume the unfinished output from standstill.
    const Ramp rp = ramp(c.ps);
    const int64_t n = p.endless ? -1 : p.paused_left;
    if (n == 0) {
      set_done(c.ps, true);
      step_done(p, t);
      transfer(p, t);
    } else {
      const Profile prof = Profile::plan(n, std::min(rp.start, p.speed_hz), p.speed_hz, rp.start, rp.acc, rp.dec);
      set_done(c.ps, false);
      a.axis.start(t, p.endless ? p.move_delta_sign : p.move_delta_sign * n, 0, p.move_forward, prof);
      p.phase = Phase::Moving;
    }
  } else if (p.phase == Phase::Homing) {
    home_check(p, t);  // inputs that no axis position drives are seen at the scans
    advance(p, t);
  } else if (p.phase == Phase::SpeedWait) {
    start_move(p, p.table.steps[p.step - 1], t);
  } else if (p.phase == Phase::Moving && !c.pau) {
    const Step& s = p.table.steps[p.step - 1];
    if ((mem_.reg(Area::R, kDynamicReg) & 0xFF) == 0x5A && s.speed.kind != Operand::Const &&
        s.motion != Motion::Drvz && !cfg_.axes[c.ps].stepspeed.used) {
      // R4056 low byte 5AH: the speed register is followed during the output.
      const int64_t v = read32(s.speed.kind, s.speed.value);
      const double hz = std::min(a.params.speed_hz(v), a.params.max_hz());
      if (v > 0 && hz >= 1 && hz <= kMaxHz && hz != p.speed_hz) {
        p.speed_hz = hz;
        const double v_out = s.motion == Motion::Drvc ? hz : a.params.start_hz();
        a.axis.retarget(t, hz, v_out, a.params.acc_hz_per_s(), a.params.dec_hz_per_s());
        if (s.motion == Motion::Drvc) p.chain_speed = a.axis.profile().end_speed();
      }
    }
    if (s.transfer == Transfer::Ext && contact(s)) {  // EXT: cut the move short, go on now
      p.paused_left = a.axis.left_if_cut(t);
      a.rest = p.paused_left;
      a.axis.cut(t);
      step_done(p, t);
      write_status(t);  // DR4072 holds the rest for the next step (manual example 1)
      go_to(p, -1, t);
      advance(p, t);
    }
  } else if (p.phase == Phase::Waiting && p.wait_until == kNever) {
    if (contact(p.table.steps[p.step - 1])) {
      go_to(p, -1, t);
      advance(p, t);
    }
  }
  if (!c.en) p.armed = true;
  p.prev_en = c.en;
  p.prev_pau = c.pau;
  p.prev_abt = c.abt;
  write_wr(p);
  write_status(t);
  write_switches(t);
  Fun140Outputs o;
  o.act = a.owner == c.instance && a.axis.moving();
  o.err = p.err;
  o.dn = p.dn;
  return o;
}

void MotionUnit::write_wr(Program& p) {
  if (p.external) return;
  const Address wr1{p.call.wr.area, Width::Word, p.call.wr.index + 1};
  uint16_t w = static_cast<uint16_t>(p.table.steps.size() & 0xFF);
  if (p.phase == Phase::Paused) w |= kWrPaused;
  if (p.phase == Phase::Homing && (p.home == Home::Md1Delay || p.home == Home::Clr)) w |= kWrWaiting;
  if (p.phase == Phase::Waiting) w |= kWrWaiting;
  if (p.endless && (p.phase == Phase::Moving || p.phase == Phase::Paused)) w |= kWrEndless;
  if (axes_[p.call.ps].axis.moving() && axes_[p.call.ps].owner == p.call.instance) w |= kWrAct;
  if (p.err) w |= kWrErr;
  if (p.dn) w |= kWrDn;
  mem_.write(wr1, w);
}

void MotionUnit::write_status(uint64_t t) {
  write_pins(t);
  for (int n = 0; n < kAxes; ++n) {
    AxisState& a = axes_[n];
    const auto put32 = [&](uint32_t reg, int64_t v) {
      mem_.set_reg(Area::R, reg, static_cast<uint16_t>(uint64_t(v) & 0xFFFF));
      mem_.set_reg(Area::R, reg + 1, static_cast<uint16_t>((uint64_t(v) >> 16) & 0xFFFF));
    };
    a.written_pos = static_cast<int32_t>(a.axis.position(t));
    put32(kPosReg + 2 * n, a.written_pos);
    put32(kFreqReg + 2 * n, std::llround(a.axis.frequency(t)));
    put32(kRemainReg + 2 * n, a.axis.moving() ? a.axis.remaining(t) : a.rest);
    mem_.set_bit(Area::M, kReadyRelay + n, a.owner == UINT32_MAX);
    mem_.set_bit(Area::M, kLastStepRelay + n, a.finished);
  }
}

// ---- unit-run programs (ROS) -----------------------------------------------------

bool MotionUnit::load_table(int ps, const Table& t, std::string* why) {
  if (ps < 0 || ps >= kAxes) return *why = "axis must be 0-3", false;
  const uint32_t id = kExternal + ps;
  if (axes_[ps].owner != UINT32_MAX && axes_[ps].owner != id) return *why = "a ladder FUN140 holds the axis", false;
  TableError e;
  if (!check_table(t, &e)) return *why = e.message, false;
  Program& p = programs_[id];
  if (p.phase != Phase::Idle && p.phase != Phase::Done) return *why = "the axis is running a table", false;
  p.external = true;
  p.call.ps = ps;
  p.call.instance = id;
  p.table = t;
  p.step = 0;
  return true;
}

bool MotionUnit::has_table(int ps) const {
  auto it = programs_.find(kExternal + ps);
  return it != programs_.end() && !it->second.table.steps.empty();
}

bool MotionUnit::program_running(int ps) const {
  auto it = programs_.find(kExternal + ps);
  if (it == programs_.end()) return false;
  const Phase ph = it->second.phase;
  return ph != Phase::Idle && ph != Phase::Done;
}

bool MotionUnit::command(int ps, Command c, std::string* why) {
  if (ps < 0 || ps >= kAxes) return *why = "axis must be 0-3", false;
  auto it = programs_.find(kExternal + ps);
  if (it == programs_.end() || it->second.table.steps.empty()) return *why = "no table loaded on this axis", false;
  Program& p = it->second;
  advance(p, now_ns_);
  switch (c) {
    case Command::Start:
      if (axes_[ps].owner != UINT32_MAX && axes_[ps].owner != p.call.instance)
        return *why = "a ladder FUN140 holds the axis", false;
      if (program_running(ps)) return *why = "already running", false;
      p.step = 0;  // from the first step
      p.armed = true;
      p.call.en = true;
      p.call.pau = p.call.abt = false;
      fun140(p.call, now_ns_ / 1000);
      return true;
    case Command::Pause:
      p.call.pau = true;
      return true;
    case Command::Resume:
      p.call.pau = false;
      return true;
    case Command::Abort:
      if (p.phase != Phase::Idle && p.phase != Phase::Done && p.phase != Phase::Stopping)
        stop(p, now_ns_, Phase::Idle, /*force_decel=*/true);
      p.call.en = false;
      p.call.pau = false;
      p.step = 0;
      return true;
  }
  return false;
}

// ---- homing (DRVZ) ------------------------------------------------------------------

void MotionUnit::configure(const AxesConfig& cfg) {
  detach_signals();
  cfg_ = cfg;
  // The YAML's parameters configure the axis from the start: a move through ROS, FUN147
  // or FUN148 ramps with them before (or without) any ladder MPARA.
  for (int n = 0; n < kAxes; ++n) axes_[n].params = cfg_.axes[n].has_params ? cfg_.axes[n].params : AxisParams();
  attach_signals();
}

bool MotionUnit::input(int ps, int x, uint64_t t) const {
  (void)ps;
  bool driven = false, on = false;
  for (int n = 0; n < kAxes; ++n)
    for (const auto& sw : cfg_.axes[n].switches)
      if (sw.x == x) {
        driven = true;
        on = on || sw.level(axes_[n].axis.position(t));
      }
  return driven ? on : mem_.bit(Area::X, x);
}

void MotionUnit::write_switches(uint64_t t) {
  for (int n = 0; n < kAxes; ++n)
    for (const auto& sw : cfg_.axes[n].switches) mem_.set_bit(Area::X, sw.x, input(n, sw.x, t));
}

void MotionUnit::run_endless(Program& p, uint64_t t, int sign, double hz) {
  AxisState& a = axes_[p.call.ps];
  const AxisParams& par = a.params;
  const Ramp rp = ramp(p.call.ps);
  if (cfg_.axes[p.call.ps].stepspeed.used) hz = std::min(hz, rp.max);  // P6 creep too: pps is the limit
  double v_in = std::min(rp.start, hz);
  if (a.axis.moving()) {
    if (a.axis.direction() == sign) v_in = a.axis.frequency(t);  // change speed on the fly
    a.axis.cut(t);
  }
  const bool forward = (sign > 0) != (par.p9_rot != 0);
  const Profile prof = Profile::plan(-1, v_in, hz, rp.start, rp.acc, rp.dec);
  a.axis.start(t, sign, 0, forward, prof);
}

void MotionUnit::start_homing(Program& p, const Step& s, uint64_t t) {
  const AxisParams& par = axes_[p.call.ps].params;
  if (s.zero_mode < 0 || s.zero_mode > 2) return fail(p, 50, t);
  if (par.dog_input() < 0 || par.dog_input() > 15) return fail(p, 51, t);
  if (s.zero_mode == 2 && (par.pg0_input() < 0 || par.pg0_input() > 15)) return fail(p, 52, t);
  if (par.clr_output() > 23) return fail(p, 53, t);
  p.phase = Phase::Homing;
  p.home = Home::Seek;  // reported below, once the start case is known
  p.home_until = kNever;
  p.pg0_count = 0;
  p.counting = false;
  p.dog_seen = false;
  p.t_cur = t;
  const int home_sign = par.p9_home ? -1 : 1;
  const bool on_dog = input(p.call.ps, par.dog_input(), t) != par.dog_nc();
  if (on_dog && par.limit_input() >= 0) {
    // Started on the DOG: toward home to the limit first, then back through the DOG
    // (manual, zero return started at or in front of the DOG).
    set_home(p, Home::ToLimit, t);
    run_endless(p, t, home_sign, p.speed_hz);
  } else if (on_dog) {
    // On the DOG with no limit to go to: leave the DOG backward first, then the
    // normal sequence (docs/motion.md "Homing"; the manual needs the limit here).
    set_home(p, Home::Escape, t);
    p.dog_seen = true;
    run_endless(p, t, -home_sign, p.speed_hz);
  } else {
    set_home(p, Home::Seek, t);
    run_endless(p, t, home_sign, p.speed_hz);
  }
  home_check(p, t);  // starting on the limit
}

void MotionUnit::set_home(Program& p, Home h, uint64_t t) {
  p.home = h;
  static const char* const kNames[] = {"seek", "to_limit", "escape", "creep", "md1_stop", "md1_delay", "md1_back", "home"};
  for (auto& f : home_obs_) f(p.call.ps, kNames[static_cast<int>(h)], t);
}

uint64_t MotionUnit::home_next_event(const Program& p) const {
  const AxisState& a = axes_[p.call.ps];
  if (p.home == Home::Md1Delay || p.home == Home::Clr) return p.home_until;
  if (p.home == Home::Md1Stop) return a.axis.end_ns();
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

void MotionUnit::home_check(Program& p, uint64_t t) {
  AxisState& a = axes_[p.call.ps];
  const AxisParams& par = a.params;
  const Step& s = p.table.steps[p.step - 1];
  const int home_sign = par.p9_home ? -1 : 1;
  const bool dog = input(p.call.ps, par.dog_input(), t) != par.dog_nc();
  const bool limit = par.limit_input() >= 0 && input(p.call.ps, par.limit_input(), t) != par.limit_nc();
  const bool pg0 = par.pg0_input() >= 0 && input(p.call.ps, par.pg0_input(), t);
  switch (p.home) {
    case Home::Seek:
      if (dog) {
        if (s.zero_mode == 1) {  // MD1: slow down and stop on the DOG
          a.axis.decelerate(t, ramp(p.call.ps).start, ramp(p.call.ps).dec);
          set_home(p, Home::Md1Stop, t);
          if (!a.axis.moving()) {
            set_home(p, Home::Md1Delay, t);
            p.home_until = t + 500000000;
          }
          return;
        }
        run_endless(p, t, home_sign, par.creep_hz());
        set_home(p, Home::Creep, t);
        p.counting = s.zero_mode == 2 && !par.pg0_rear();
        p.prev_pg0 = pg0;
        p.pg0_count = 0;
        if (p.counting && par.p17_pg0 == 0) return home_found(p, t);
      } else if (limit) {  // in front of the DOG: back until the DOG has been passed
        a.axis.cut(t);
        run_endless(p, t, -home_sign, p.speed_hz);
        set_home(p, Home::Escape, t);
        p.dog_seen = false;
      }
      return;
    case Home::ToLimit:  // started on the DOG: the DOG is ignored until the limit acts
      if (limit) {
        a.axis.cut(t);
        run_endless(p, t, -home_sign, p.speed_hz);
        set_home(p, Home::Escape, t);
        p.dog_seen = dog;
      }
      return;
    case Home::Escape:
      if (dog) p.dog_seen = true;
      if (p.dog_seen && !dog) {
        a.axis.cut(t);
        run_endless(p, t, home_sign, p.speed_hz);
        set_home(p, Home::Seek, t);
      }
      return;
    case Home::Creep:
      if (s.zero_mode == 0) {
        if (!dog) home_found(p, t);
        return;
      }
      if (!p.counting && !dog) {  // MD2 rear edge: count from leaving the DOG
        p.counting = true;
        p.prev_pg0 = pg0;
        if (par.p17_pg0 == 0) return home_found(p, t);
        return;
      }
      if (p.counting && pg0 && !p.prev_pg0 && ++p.pg0_count >= par.p17_pg0) return home_found(p, t);
      p.prev_pg0 = pg0;
      return;
    case Home::Md1Stop:
      if (a.axis.moving() && t >= a.axis.end_ns()) a.axis.settle(t);
      if (!a.axis.moving() || t >= a.axis.end_ns()) {
        a.axis.settle(t);
        set_home(p, Home::Md1Delay, t);
        p.home_until = t + 500000000;  // 0.5 s, then back out of the DOG
      }
      return;
    case Home::Md1Delay:
      if (t >= p.home_until) {
        p.home_until = kNever;
        run_endless(p, t, -home_sign, par.creep_hz());
        set_home(p, Home::Md1Back, t);
        if (!dog) home_found(p, t);
      }
      return;
    case Home::Md1Back:
      if (!dog) home_found(p, t);
      return;
    case Home::Clr:
      if (t >= p.home_until) {
        // No CLR output (FFH): done at once; there is no Y to switch off.
        if (par.clr_output() >= 0) mem_.set_bit(Area::Y, par.clr_output(), false);
        p.home_until = kNever;
        a.axis.set_position(par.p16_zero);
        p.phase = Phase::Moving;  // for the step bookkeeping
        p.paused_left = 0;
        a.rest = 0;
        set_done(p.call.ps, true);  // the home step is complete
        step_done(p, t);
        transfer(p, t);
      }
      return;
  }
}

void MotionUnit::home_found(Program& p, uint64_t t) {
  AxisState& a = axes_[p.call.ps];
  a.axis.cut(t);
  set_home(p, Home::Clr, t);
  p.home_until = t;
  if (a.params.clr_output() >= 0) {
    mem_.set_bit(Area::Y, a.params.clr_output(), true);
    p.home_until = t + 20000000;  // CLR on for 20 ms, then done
  } else {
    home_check(p, t);
  }
}

bool MotionUnit::fun141(int ps, const Address& sr) {
  if (ps < 0 || ps >= kAxes) return false;
  if (sr.index + kParamWords > Memory::word_count(sr.area)) return false;
  const AxisParams p = AxisParams::from_registers(mem_.words(sr.area) + sr.index);
  const int code = p.validate();
  if (code != 0) {
    mem_.set_reg(Area::R, kErrReg + ps, static_cast<uint16_t>(code));
    return false;
  }
  axes_[ps].params = p;
  return true;
}

void MotionUnit::fun142(int ps, uint64_t now_us) {
  if (ps < 0 || ps >= kAxes) return;
  const uint64_t t = now_us * 1000;
  for (auto& kv : programs_) {
    Program& p = kv.second;
    if (p.call.ps != ps) continue;
    advance(p, t);
    if (p.phase == Phase::Moving || p.phase == Phase::Waiting || p.phase == Phase::SpeedWait || p.phase == Phase::Paused)
      stop(p, t, Phase::Idle);
  }
  interp_->psoff(ps, t);  // FUN147 and FUN148 outputs on the axis stop too
  mpg_->psoff(ps, t);
  write_status(t);
}

MotionUnit::Ramp MotionUnit::ramp(int ps) const {
  const StepSpeed& ss = cfg_.axes[ps].stepspeed;
  if (ss.used) return {ss.start_hz(), ss.max_hz(), ss.accel(), ss.accel()};
  const AxisParams& par = axes_[ps].params;
  return {par.start_hz(), par.max_hz(), par.acc_hz_per_s(), par.dec_hz_per_s()};
}

void MotionUnit::set_done(int ps, bool on) {
  const int m = cfg_.axes[ps].stepspeed.done;
  if (cfg_.axes[ps].stepspeed.used && m >= 0) mem_.set_bit(Area::M, static_cast<uint32_t>(m), on);
}

int64_t MotionUnit::fun143(int ps) const { return axes_[ps].params.pulses_to_ut(axes_[ps].axis.position(now_ns_)); }

int MotionUnit::step(int ps) const {
  for (const auto& kv : programs_)
    if (kv.second.call.ps == ps && axes_[ps].owner == kv.first) return kv.second.step;
  return 0;
}
bool MotionUnit::busy(int ps) const { return axes_[ps].owner != UINT32_MAX; }
bool MotionUnit::finished(int ps) const { return axes_[ps].finished; }
int MotionUnit::error(int ps) const { return mem_.reg(Area::R, kErrReg + ps); }

}  // namespace motion
}  // namespace plc_cell
