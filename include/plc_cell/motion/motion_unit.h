#pragma once
// The pulse-output axes PSO0-PSO3 of one soft PLC, as a scan hook and an event source of
// the cell's scheduler (docs/motion.md). The unit composes the axis components and
// gives them one clock:
//   Positioning (positioning.h)    FUN140 programs, step by step, and tables run without a ladder
//   Homing (homing.h)              DRVZ, the zero return of a FUN140 step
//   move_plan.h, Profile           a step's pulses and closed-form speed profile
//   Ramps (ramps.h)                FUN141's ramp or the `stepspeed:` step form
//   Interpolation (interpolation.h) FUN147 linear interpolation
//   Mpg (mpg.h)                    FUN148 handwheel
//   Switches, AxisWiring, StatusRegisters: the simulated switches, the pins and their
//   wiring into the counters, the status relays and registers.
//
// Virtual time: each axis's move is a closed-form Profile, so its end instant,
// position and frequency at any instant cost O(1). Before each program scan the
// unit advances every program from event to event (move ends, WAIT/ACT times) up
// to the scan's instant, starting the next steps at the exact instants; contacts
// (WAIT Xn, EXT Xn) and EN/PAU/ABT are seen at the scans. Status relays and
// registers (M1991-M1999, R4056-R4067, DR4072-DR4094) are written at every scan.
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/motion/axis.h"
#include "plc_cell/motion/axis_config.h"
#include "plc_cell/motion/axis_state.h"
#include "plc_cell/motion/axis_wiring.h"
#include "plc_cell/motion/homing.h"
#include "plc_cell/motion/params.h"
#include "plc_cell/motion/positioning.h"
#include "plc_cell/motion/program.h"
#include "plc_cell/motion/pulse_pins.h"
#include "plc_cell/motion/ramps.h"
#include "plc_cell/motion/status_registers.h"
#include "plc_cell/motion/switches.h"
#include "plc_cell/motion/table.h"
#include "plc_cell/timeline/event_source.h"
#include "plc_cell/timeline/scheduler.h"

namespace plc_cell {

class Plc;
class Memory;

namespace motion {

class Interpolation;  // FUN147 (interpolation.h)
class Mpg;            // FUN148 (mpg.h)

class MotionUnit final : public ScanHook, public timeline::EventSource {
 public:
  explicit MotionUnit(Plc& plc);
  ~MotionUnit() override;
  MotionUnit(const MotionUnit&) = delete;
  MotionUnit& operator=(const MotionUnit&) = delete;

  static MotionUnit* of(ScanEngine* engine);

  void before_program(uint64_t now_us) override;
  void after_program(uint64_t now_us) override;
  void on_stop() override;
  void attached(ScanEngine& e) override;  // FUN handlers find the unit through of()
  void detached(ScanEngine& e) override;
  // In the cell's scheduler (timeline/scheduler.h), with the counters: step ends and
  // WAIT/ACT times happen at their instants, and PSOnI is requested there.
  uint64_t next_event_ns() override;
  void at(uint64_t t_ns) override;

  // ---- instructions (lock held) ----
  Fun140Outputs fun140(const Fun140Call& c, uint64_t now_us) {
    touch();
    return positioning_.fun140(c, now_us);
  }
  bool fun141(int ps, const Address& sr);  // false: invalid, code in R4060+ps
  void fun142(int ps, uint64_t now_us);    // PSOFF: stop the output (M1991 decides how)
  int64_t fun143(int ps) const;            // PSCNV: position in Ut

  // ---- control without a ladder FUN140 (ROS services and actions; lock held) ----
  // A table run by the unit itself on axis ps, as if by a FUN140 whose EN/PAU/ABT
  // are the commands below. False (with *why) if a ladder FUN140 holds the axis.
  bool load_table(int ps, const Table& t, std::string* why) {
    touch();
    return positioning_.load_table(ps, t, why);
  }
  using Command = ProgramCommand;
  // Abort decelerates to P5 whatever M1991 says (an operator's stop).
  bool command(int ps, Command c, std::string* why) {
    touch();
    return positioning_.command(ps, c, why);
  }
  bool has_table(int ps) const { return positioning_.has_table(ps); }
  // State of the unit-run program: running, done (last step finished), error code.
  bool program_running(int ps) const { return positioning_.program_running(ps); }

  // The cell YAML's axes: section (names, output modes, simulated switches). Axes
  // with `output:` own their pins Y2n/Y2n+1; `wiring:` and `encoder:` become edge
  // sources of the counters (throws SourceError naming the YAML line if they clash).
  void configure(const AxesConfig& cfg);
  // The pins of axis ps (null unless configured with `output:`), docs/motion.md "Pulse pins".
  const AxisSignal* pins(int ps) const { return wiring_.pins(ps); }
  const AxesConfig& config() const { return cfg_; }

  // ---- observation and control (lock held) ----
  const Axis& axis(int ps) const { return axes_[ps].axis; }
  const AxisParams& params(int ps) const { return axes_[ps].params; }
  void set_params(int ps, const AxisParams& p) {
    touch();
    axes_[ps].params = p;
  }
  int64_t position(int ps) const { return axes_[ps].axis.position(now_ns_); }
  double frequency(int ps) const { return axes_[ps].axis.frequency(now_ns_); }
  int step(int ps) const { return positioning_.step(ps); }  // step being run (WR+0), 0 if none
  bool busy(int ps) const { return axes_[ps].owner != kFree; }  // a program holds the axis
  bool finished(int ps) const { return axes_[ps].finished; }  // M1996+ps
  int error(int ps) const;           // R4060+ps
  uint64_t now_ns() const { return now_ns_; }
  // ---- FUN147 / FUN148 (interpolation.h, mpg.h): they hold axes as a FUN140 does ----
  Interpolation& interpolation() {
    touch();
    return *interp_;
  }
  Mpg& mpg() {
    touch();
    return *mpg_;
  }
  uint32_t owner(int ps) const { return axes_[ps].owner; }  // kFree (UINT32_MAX): free (M1992+ps on)
  void take_axis(int ps, uint32_t owner) {
    touch();
    axes_[ps].owner = owner;
  }
  void release_axis(int ps, uint32_t owner) {
    touch();
    if (axes_[ps].owner == owner) axes_[ps].owner = kFree;
  }
  Axis& drive(int ps) {
    touch();
    return axes_[ps].axis;
  }
  void set_rest(int ps, int64_t rest) {  // DR4072 while idle
    touch();
    axes_[ps].rest = rest;
  }
  // Every step completion, with its exact instant (tests, ROS feedback).
  using StepObserver = std::function<void(int ps, int step, uint64_t t_ns)>;
  void on_step_done(StepObserver f) { positioning_.on_step_done(std::move(f)); }
  // Every DRVZ phase change at its instant: seek, to_limit, escape, creep, md1_stop,
  // md1_delay, md1_back, home (docs/motion.md "Homing"; `plc_cell sim --trace`).
  using HomeObserver = std::function<void(int ps, const char* phase, uint64_t t_ns)>;
  void on_home_phase(HomeObserver f) { homing_.on_phase(std::move(f)); }

 private:
  void advance(uint64_t t);
  void write_status(uint64_t t) { status_.write(t); }
  // Nothing to advance between scans or at a scan: no program, group or handwheel holds
  // an axis, no axis moves, and no pin or switch follows one. Most cells, most scans.
  // Kept for the revision it was found at.
  bool quiet() const {
    if (quiet_revision_ != revision_) {
      quiet_ = find_quiet();
      quiet_revision_ = revision_;
    }
    return quiet_;
  }
  bool find_quiet() const;
  // Every member that may change an axis, a program, a group or a handwheel counts
  // one: a quiet unit whose revision stands still has the state it had at its last
  // status write, so while the status block holds what was written, that write stands
  // (docs/motion.md "Status").
  void touch() { ++revision_; }
  // The status of a quiet unit, written only if its revision or the block changed.
  void write_quiet_status(uint64_t t) {
    // The block as written at this revision: DR4088 holds what was written, so there is
    // no ladder position to adopt, and the status would be written again unchanged.
    if (revision_ != status_revision_ || !status_.holds()) rewrite_quiet_status(t);
  }
  void rewrite_quiet_status(uint64_t t);

  Plc& plc_;
  ScanEngine& engine_;
  Memory& mem_;
  timeline::Scheduler& sched_;
  hsc::HscUnit* hsc_;  // the counters' unit (pins, encoders, MPG counts), if any
  AxesConfig cfg_;
  uint64_t now_ns_ = 0;
  bool preloaded_ = false;  // the YAML's tables written since RUN
  bool wired_ = false;      // the YAML gives some axis pins or switches
  uint64_t revision_ = 0;
  mutable uint64_t quiet_revision_ = UINT64_MAX;  // quiet_ was found at this revision
  mutable bool quiet_ = false;
  uint64_t status_revision_ = UINT64_MAX;  // the last status written while quiet
  AxisStates axes_;
  Ramps ramps_{cfg_, axes_, mem_};
  Switches switches_{cfg_, axes_, mem_};
  AxisWiring wiring_{cfg_, axes_, mem_, hsc_};
  StatusRegisters status_{mem_, axes_, wiring_};
  Homing homing_{mem_, axes_, cfg_, ramps_, switches_};
  Positioning positioning_{{mem_, sched_, axes_, now_ns_, ramps_, homing_, status_, switches_}};
  std::unique_ptr<Interpolation> interp_;
  std::unique_ptr<Mpg> mpg_;
};

}  // namespace motion
}  // namespace plc_cell
