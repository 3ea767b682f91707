// The axes of one soft PLC: the components on one clock, as a scan hook and an event
// source of the cell's scheduler (docs/motion.md).
#include "plc_cell/motion/motion_unit.h"

#include <algorithm>

#include "plc_cell/core/memory.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/motion/interpolation.h"
#include "plc_cell/motion/mpg.h"
#include "plc_cell/motion/preload.h"

namespace plc_cell {
namespace motion {

namespace {
ScanEngine& engine_of(Plc& p) { return *p.locked([](ScanEngine& e, Memory&) { return &e; }); }
Memory& memory_of(Plc& p) { return *p.locked([](ScanEngine&, Memory& m) { return &m; }); }
timeline::Scheduler& scheduler_of(Plc& p) {
  return *p.locked([](ScanEngine& e, Memory&) { return &timeline::Scheduler::of(e); });
}
hsc::HscUnit* counters_of(Plc& p) { return p.locked([](ScanEngine& e, Memory&) { return hsc::HscUnit::of(&e); }); }
}  // namespace

MotionUnit::MotionUnit(Plc& plc)
    : plc_(plc), engine_(engine_of(plc)), mem_(memory_of(plc)), sched_(scheduler_of(plc)), hsc_(counters_of(plc)) {
  plc_.locked([this](ScanEngine& e, Memory&) {
    e.add_hook(this);
    sched_.add_source(this);
  });
  interp_ = std::make_unique<Interpolation>(*this, mem_);
  mpg_ = std::make_unique<Mpg>(*this, mem_, hsc_);
}

MotionUnit::~MotionUnit() {
  plc_.locked([this](ScanEngine& e, Memory&) {
    if (hsc_ && hsc::HscUnit::of(&e) == hsc_) wiring_.detach();
    sched_.remove_source(this);
    e.remove_hook(this);
  });
}

MotionUnit* MotionUnit::of(ScanEngine* engine) { return engine ? engine->extensions().get<MotionUnit>() : nullptr; }

void MotionUnit::attached(ScanEngine& e) { e.extensions().attach(this); }
void MotionUnit::detached(ScanEngine& e) { e.extensions().detach(this); }

bool MotionUnit::find_quiet() const {
  if (wired_) return false;
  for (const AxisState& a : axes_)
    if (a.axis.moving()) return false;
  return positioning_.idle() && interp_->idle() && mpg_->idle();
}

uint64_t MotionUnit::next_event_ns() {
  if (quiet()) return kNever;
  return std::min({positioning_.next_event_ns(), interp_->next_event_ns(), mpg_->next_event_ns()});
}

void MotionUnit::at(uint64_t t) {
  if (next_event_ns() > t) return;  // another subsystem's instant
  touch();
  status_.adopt_ladder_positions();
  advance(t);
  write_status(t);  // the routines of this instant read its position, frequency, ...
}

void MotionUnit::before_program(uint64_t now_us) {
  const uint64_t t = now_us * 1000;
  if (!preloaded_) {
    preloaded_ = true;
    preload_tables(mem_, cfg_);
  }
  if (quiet()) {  // what advance, the unit's tables, the pins and the switches come to then
    now_ns_ = std::max(now_ns_, t);
    interp_->write_status(t);  // with no group it compares first (interpolation.h)
    write_quiet_status(t);
    return;
  }
  touch();
  status_.adopt_ladder_positions();
  advance(t);
  positioning_.run_unit_programs(now_us);
  write_status(t);
  switches_.write(t);
}

void MotionUnit::after_program(uint64_t now_us) {
  const uint64_t t = now_us * 1000;
  if (quiet()) {
    write_quiet_status(t);
    return;
  }
  // A ladder write of DR4088 in this scan sets an idle axis's position before the status
  // is written over it (homing by ladder: the manual's methods 1 and 2 write 0 there).
  if (status_.adopt_ladder_positions()) touch();
  write_status(t);
}

void MotionUnit::rewrite_quiet_status(uint64_t t) {
  if (status_.adopt_ladder_positions()) touch();
  write_status(t);
  status_revision_ = revision_;
}

void MotionUnit::on_stop() {
  touch();
  preloaded_ = false;
  for (auto& a : axes_) {
    a.axis.cut(now_ns_);
    a.owner = kFree;
  }
  positioning_.on_stop();
  interp_->on_stop();
  mpg_->on_stop();
}

void MotionUnit::advance(uint64_t t) {
  positioning_.advance(t);
  interp_->advance(t);  // FUN147 groups and FUN148 outputs on the same clock
  mpg_->advance(t);
  now_ns_ = std::max(now_ns_, t);
}

void MotionUnit::configure(const AxesConfig& cfg) {
  touch();
  wiring_.detach();
  wired_ = true;  // until the new wiring is known: a failed attach leaves the full scan path
  cfg_ = cfg;
  // The YAML's parameters configure the axis from the start: a move through ROS, FUN147
  // or FUN148 ramps with them before (or without) any ladder MPARA.
  for (int n = 0; n < kAxes; ++n) axes_[n].params = cfg_.axes[n].has_params ? cfg_.axes[n].params : AxisParams();
  wiring_.attach();
  wired_ = false;
  for (int n = 0; n < kAxes; ++n) wired_ = wired_ || wiring_.pins(n) || !cfg_.axes[n].switches.empty();
}

bool MotionUnit::fun141(int ps, const Address& sr) {
  touch();
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
  touch();
  if (ps < 0 || ps >= kAxes) return;
  const uint64_t t = now_us * 1000;
  positioning_.psoff(ps, t);
  interp_->psoff(ps, t);  // FUN147 and FUN148 outputs on the axis stop too
  mpg_->psoff(ps, t);
  write_status(t);
}

int64_t MotionUnit::fun143(int ps) const { return axes_[ps].params.pulses_to_ut(axes_[ps].axis.position(now_ns_)); }

int MotionUnit::error(int ps) const { return mem_.reg(Area::R, kErrReg + ps); }

}  // namespace motion
}  // namespace plc_cell
