// FUN147 MHSP0 linear interpolation in virtual time (docs/motion.md "FUN147").
#include "plc_cell/motion/interpolation.h"

#include <algorithm>
#include <cmath>

#include "plc_cell/core/memory.h"
#include "plc_cell/motion/params.h"
#include "plc_cell/motion/motion_unit.h"
#include "step_flow.h"

namespace plc_cell {
namespace motion {

namespace {
constexpr uint32_t kGroupErrReg = 4060;    // D4060+gp
constexpr uint32_t kGroupStepReg = 4062;   // D4062+gp
using flow::kTimeUnitNs;
using flow::kMaxStepsPerInstant;
using flow::kWrPaused;
using flow::kWrWaiting;
using flow::kWrAct;
using flow::kWrErr;
using flow::kWrDn;

bool has(uint8_t mask, int n) { return (mask >> n) & 1; }
}  // namespace

// ---- events -----------------------------------------------------------------------

uint64_t Interpolation::move_end(const Group& g) const {
  uint64_t end = 0;  // every axis already stopped: due now
  for (int n = 0; n < 4; ++n)
    if (has(g.moving, n) && unit_.axis(n).moving()) end = std::max(end, unit_.axis(n).end_ns());
  return end;
}

uint64_t Interpolation::next_event(const Group& g) const {
  if (g.phase == Phase::Moving || g.phase == Phase::Stopping) return move_end(g);
  if (g.phase == Phase::Waiting) return g.wait_until;
  return kNever;
}

uint64_t Interpolation::next_event_ns() const {
  uint64_t next = kNever;
  for (const auto& kv : groups_) next = std::min(next, next_event(kv.second));
  return next;
}

void Interpolation::advance(uint64_t t) {
  for (auto& kv : groups_) advance(kv.second, t);
  write_status(t);
}

void Interpolation::advance(Group& g, uint64_t t) {
  for (int guard = 0; guard < kMaxStepsPerInstant; ++guard) {
    const uint64_t next = next_event(g);
    if (next == kNever || next > t) return;
    if (g.phase == Phase::Moving) {
      for (int n = 0; n < 4; ++n)
        if (has(g.moving, n)) {
          unit_.drive(n).settle(next);
          unit_.set_rest(n, 0);
        }
      g.moving = 0;
      g.rest = {};
      step_done(g, next);
      transfer(g, next);
    } else if (g.phase == Phase::Stopping) {
      cut(g, next);  // every axis has reached its stop: keep what is left per axis
      g.phase = g.after_stop;
      if (g.phase != Phase::Paused) release(g);
    } else {  // Waiting: WAIT Time
      go_to(g, -1, next);
    }
  }
  fail(g, 34, t);  // a GOTO loop of empty steps
}

// ---- steps --------------------------------------------------------------------------

void Interpolation::start_step(Group& g, int k, uint64_t t) {
  g.step = k;
  g.wait_until = kNever;
  mem_.write({g.call.wr.area, Width::Word, g.call.wr.index}, static_cast<uint16_t>(k));
  start_move(g, g.table.steps[k - 1], t);
}

void Interpolation::start_move(Group& g, const LinStep& s, uint64_t t) {
  const int64_t v = flow::value32(mem_, s.flow.speed);
  if (v == 0) {  // SPD 0: wait until the speed register becomes non-zero (as FUN140)
    g.phase = Phase::SpeedWait;
    return;
  }
  std::array<int64_t, 4> delta{};
  int lead = -1;
  for (int n = 0; n < 4; ++n) {
    if (!has(s.axes, n)) continue;
    const int64_t stroke = flow::value32(mem_, s.stroke[n]);
    if (stroke < -99999999 || stroke > 99999999) return fail(g, 33, t);
    const int64_t pulses = s.ut ? unit_.params(n).ut_to_pulses(stroke) : stroke;
    delta[n] = s.abs ? pulses - unit_.axis(n).position(t) : pulses;
    if (std::llabs(delta[n]) > 2147483647LL) return fail(g, 40, t);
    if (lead < 0 || std::llabs(delta[n]) > std::llabs(delta[lead])) lead = n;
  }
  // The vector speed is converted with the lead axis's units (P0 = 0: machine speed).
  const double hz = unit_.params(lead < 0 ? 0 : lead).speed_hz(v);
  if (v < 0 || hz > kMaxHz || hz < 1) return fail(g, 31, t);
  g.vspeed = hz;
  if (lead < 0 || delta[lead] == 0) {  // nothing to move: the step completes at once
    g.chain = false;
    step_done(g, t);
    return transfer(g, t);
  }
  move(g, delta, hz, g.chain ? g.chain_v : 0.0, s.line, t);
}

void Interpolation::move(Group& g, const std::array<int64_t, 4>& delta, double v, double v_in, bool line,
                         uint64_t t) {
  double len2 = 0;
  int lead = 0;
  for (int n = 0; n < 4; ++n) {
    len2 += double(delta[n]) * double(delta[n]);
    if (std::llabs(delta[n]) > std::llabs(delta[lead])) lead = n;
  }
  const double len = std::sqrt(len2);            // Euclidean path length, pulses
  const double big = double(std::llabs(delta[lead]));
  for (int n = 0; n < 4; ++n)  // no axis above its own P4
    if (delta[n] != 0) v = std::min(v, unit_.params(n).max_hz() * len / std::llabs(delta[n]));
  v_in = std::min(v_in, v);
  // P13 of the lead axis: the time from 0 to the programmed speed (and back).
  const double t13 = unit_.params(lead).p13_interp_ms / 1000.0;
  g.acc = t13 > 0 ? v / t13 : kInf;
  // The lead axis's profile; every other axis runs it scaled by |d_n| / |d_lead|.
  const double k = big / len;
  const Profile lead_prof = Profile::plan(std::llabs(delta[lead]), v_in * k, v * k, line ? v * k : 0.0, g.acc * k,
                                          g.acc * k);
  g.moving = 0;
  for (int n = 0; n < 4; ++n) {
    g.scale[n] = double(std::llabs(delta[n])) / len;
    if (delta[n] == 0) continue;
    const int64_t m = std::llabs(delta[n]);
    unit_.drive(n).start(t, delta[n], 0, delta[n] > 0, lead_prof.scaled(double(m) / big, m));
    g.moving |= uint8_t(1u << n);
  }
  g.phase = Phase::Moving;
  g.chain = line;
  g.chain_v = lead_prof.end_speed() / k;
}

void Interpolation::step_done(Group& g, uint64_t t) {
  g.dn = true;
  mem_.set_reg(Area::D, kGroupStepReg + g.call.gp, static_cast<uint16_t>(g.step));
  write_wr(g);
  for (auto& f : obs_) f(g.call.gp, g.step, t);
}

void Interpolation::transfer(Group& g, uint64_t t) {
  const Step& s = g.table.steps[g.step - 1].flow;
  switch (s.transfer) {
    case Transfer::WaitTime:
      g.phase = Phase::Waiting;
      g.wait_until = t + uint64_t(flow::time16(mem_, s)) * kTimeUnitNs;
      return;
    case Transfer::WaitContact:
    case Transfer::Ext:
      if (flow::contact(mem_, s)) return go_to(g, -1, t);
      g.phase = Phase::Waiting;
      g.wait_until = kNever;  // the contact is looked at every scan
      return;
    default:
      return go_to(g, -1, t);
  }
}

void Interpolation::go_to(Group& g, int target, uint64_t t) {
  const Step& s = g.table.steps[g.step - 1].flow;
  const int n = static_cast<int>(g.table.steps.size());
  if (target < 0 && (target = flow::goto_target(mem_, s, g.step, n)) == 0) return fail(g, 34, t);
  if (target > n) {  // past the last step: finished (M1934+gp)
    g.phase = Phase::Done;
    g.chain = false;
    finished_[g.call.gp] = true;
    release(g);
    return;
  }
  start_step(g, target, t);
}

// ---- stopping -------------------------------------------------------------------------

void Interpolation::cut(Group& g, uint64_t t) {
  for (int n = 0; n < 4; ++n) {
    if (!has(g.moving, n)) continue;
    Axis& ax = unit_.drive(n);
    g.rest[n] = ax.moving() ? ax.left_if_cut(t) * ax.direction() : 0;
    unit_.set_rest(n, std::llabs(g.rest[n]));
    ax.cut(t);
  }
}

void Interpolation::stop(Group& g, uint64_t t, Phase then) {
  g.chain = false;
  if (g.phase == Phase::Moving) {
    if (mem_.bit(Area::M, kDecelRelay)) {
      // Each axis slows at its share of the vector rate, to its next whole pulse.
      bool any = false;
      for (int n = 0; n < 4; ++n) {
        if (!has(g.moving, n)) continue;
        Axis& ax = unit_.drive(n);
        const double dec = g.acc * g.scale[n];
        const double v_stop = std::max(1.0, unit_.params(n).start_hz() * g.scale[n]);
        g.rest[n] = ax.left_if_cut(t) * ax.direction();
        ax.decelerate(t, v_stop, dec);
        any = any || ax.moving();
      }
      if (any) {
        g.phase = Phase::Stopping;
        g.after_stop = then;
        return;
      }
    }
    cut(g, t);
  }
  g.phase = then;
  if (then != Phase::Paused) release(g);
}

void Interpolation::release(Group& g) {
  for (int n = 0; n < 4; ++n)
    if (has(g.held, n)) unit_.release_axis(n, owner(g));
  g.held = 0;
  g.moving = 0;
}

void Interpolation::fail(Group& g, int code, uint64_t t) {
  for (int n = 0; n < 4; ++n)
    if (has(g.moving, n)) unit_.drive(n).cut(t);
  release(g);
  g.phase = Phase::Idle;
  g.chain = false;
  g.err = true;
  mem_.set_reg(Area::D, kGroupErrReg + g.call.gp, static_cast<uint16_t>(code));
  write_wr(g);
}

bool Interpolation::load(Group& g) {
  const Address& sr = g.call.sr;
  TableError e;
  LinTable t;
  if (!decode_lin_table(mem_.words(sr.area) + sr.index, Memory::word_count(sr.area) - sr.index, &t, &e)) {
    g.table = {};
    fail(g, e.code, 0);
    return false;
  }
  // AMBIG-24: Gp1 is the pair Ps2 & Ps3; three- and four-axis interpolation is Gp0's.
  if (g.call.gp == 1 && (t.axes() & 0x3)) {
    g.table = {};
    fail(g, kIllegalLin, 0);
    return false;
  }
  g.table = std::move(t);
  return true;
}

// ---- the instruction ---------------------------------------------------------------

Fun147Outputs Interpolation::fun147(const Fun147Call& c, uint64_t t) {
  if (c.gp < 0 || c.gp > 1) return {};
  Group& g = groups_[c.instance];
  g.call = c;
  advance(g, t);
  if (!(mem_.read({c.wr.area, Width::Word, c.wr.index + 1}) & kWrDn)) g.dn = false;  // the user cleared WR+1
  const bool active = g.phase != Phase::Idle && g.phase != Phase::Done;
  if (c.abt) {
    if (active && g.phase != Phase::Stopping) stop(g, t, Phase::Idle);
    g.step = 0;
    mem_.write({c.wr.area, Width::Word, c.wr.index}, 0);
  } else if (!c.en) {
    if (active && g.phase != Phase::Stopping) stop(g, t, Phase::Idle);
  } else if (!active) {
    // EN = 1: load the table; start at the next step once every axis it names is free.
    if (g.armed && !load(g)) {
      g.armed = false;  // a bad table is reported once per EN; nothing moves
    } else if (g.armed) {
      const uint8_t axes = g.table.axes();
      bool free = true;
      for (int n = 0; n < 4; ++n)
        if (has(axes, n)) {
          const uint32_t o = unit_.owner(n);
          free = free && (o == UINT32_MAX || o == owner(g)) && !unit_.axis(n).moving();
        }
      if (free) {
        g.armed = false;
        g.err = false;
        finished_[c.gp] = false;
        for (int n = 0; n < 4; ++n)
          if (has(axes, n)) unit_.take_axis(n, owner(g));
        g.held = axes;
        g.chain = false;
        const int n = static_cast<int>(g.table.steps.size());
        const int cur = static_cast<int16_t>(mem_.read({c.wr.area, Width::Word, c.wr.index}));
        start_step(g, cur <= 0 || cur >= n ? 1 : cur + 1, t);
        advance(g, t);
      }
    }
  } else if (c.pau && !g.prev_pau && g.phase == Phase::Moving) {
    stop(g, t, Phase::Paused);
  } else if (!c.pau && g.phase == Phase::Paused) {
    // Resume: the unfinished pulses of every axis, again as one linear move from 0.
    if (std::all_of(g.rest.begin(), g.rest.end(), [](int64_t r) { return r == 0; })) {
      step_done(g, t);
      transfer(g, t);
    } else {
      move(g, g.rest, g.vspeed, 0.0, g.table.steps[g.step - 1].line, t);
    }
  } else if (g.phase == Phase::SpeedWait) {
    start_move(g, g.table.steps[g.step - 1], t);
  } else if (g.phase == Phase::Moving && !c.pau) {
    const Step& s = g.table.steps[g.step - 1].flow;
    if (s.transfer == Transfer::Ext && flow::contact(mem_, s)) {  // EXT: cut the move short, go on now
      cut(g, t);
      g.moving = 0;
      step_done(g, t);
      go_to(g, -1, t);
      advance(g, t);
    }
  } else if (g.phase == Phase::Waiting && g.wait_until == kNever) {
    if (flow::contact(mem_, g.table.steps[g.step - 1].flow)) {
      go_to(g, -1, t);
      advance(g, t);
    }
  }
  if (!c.en) g.armed = true;
  g.prev_pau = c.pau;
  write_wr(g);
  write_status(t);
  Fun147Outputs o;
  for (int n = 0; n < 4; ++n) o.act = o.act || (has(g.held, n) && unit_.axis(n).moving() && t < unit_.axis(n).end_ns());
  o.err = g.err;
  o.dn = g.dn;
  return o;
}

void Interpolation::write_wr(Group& g) {
  uint16_t w = static_cast<uint16_t>(g.table.steps.size() & 0xFF);
  if (g.phase == Phase::Paused) w |= kWrPaused;
  if (g.phase == Phase::Waiting) w |= kWrWaiting;
  if (g.phase == Phase::Moving || g.phase == Phase::Stopping) w |= kWrAct;
  if (g.err) w |= kWrErr;
  if (g.dn) w |= kWrDn;
  mem_.write({g.call.wr.area, Width::Word, g.call.wr.index + 1}, w);
}

double Interpolation::vector_speed(int gp, uint64_t t) const {
  if (groups_.empty()) return 0;  // most cells, most scans
  double s2 = 0;
  for (const auto& kv : groups_) {
    if (kv.second.call.gp != gp) continue;
    for (int n = 0; n < 4; ++n)
      if (has(kv.second.held, n)) s2 += std::pow(unit_.axis(n).frequency(t), 2);
  }
  return std::sqrt(s2);
}

void Interpolation::rewrite_status(uint64_t t) {
  const bool idle = groups_.empty();  // then the speeds are 0
  for (int gp = 0; gp < 2; ++gp) {
    const double speed = vector_speed(gp, t);  // 0 without a moving group: no rounding to do
    const uint32_t v = speed == 0 ? 0 : static_cast<uint32_t>(std::llround(speed));
    mem_.set_reg(Area::R, kVectorReg + 2 * gp, static_cast<uint16_t>(v & 0xFFFF));
    mem_.set_reg(Area::R, kVectorReg + 2 * gp + 1, static_cast<uint16_t>(v >> 16));
    mem_.set_bit(Area::M, kGroupDoneRelay + gp, finished_[gp]);
  }
  if (idle) {
    written_finished_ = finished_;
    written_.take(mem_);
  } else {
    written_.forget();
  }
}

void Interpolation::psoff(int ps, uint64_t t) {
  for (auto& kv : groups_) {
    Group& g = kv.second;
    if (!has(g.held, ps)) continue;
    advance(g, t);
    if (g.phase == Phase::Moving || g.phase == Phase::Waiting || g.phase == Phase::SpeedWait ||
        g.phase == Phase::Paused)
      stop(g, t, Phase::Idle);
  }
  write_status(t);
}

void Interpolation::on_stop() {
  groups_.clear();
  finished_ = {};
}

}  // namespace motion
}  // namespace plc_cell
