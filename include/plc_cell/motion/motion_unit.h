#pragma once
// The pulse-output axes PSO0-PSO3 of one soft PLC and the FUN140 positioning
// programs that drive them, as a scan hook (docs/motion.md).
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
#include "plc_cell/motion/params.h"
#include "plc_cell/motion/pulse_pins.h"
#include "plc_cell/motion/table.h"
#include "plc_cell/timeline/event_source.h"
#include "plc_cell/timeline/scheduler.h"

namespace plc_cell {

class Plc;
class Memory;

namespace motion {

constexpr int kAxes = 4;
constexpr uint32_t kDecelRelay = 1991;  // M1991: stop/pause with deceleration (FUN140/142/147/148)

class Interpolation;  // FUN147 (interpolation.h)
class Mpg;            // FUN148 (mpg.h)

// What a FUN140 instruction sees this scan.
struct Fun140Call {
  int ps = 0;
  Address sr{}, wr{};
  bool en = false, pau = false, abt = false;
  uint32_t instance = 0;
};
struct Fun140Outputs {
  bool act = false, err = false, dn = false;
};

class MotionUnit : public ScanHook, public timeline::EventSource {
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
  Fun140Outputs fun140(const Fun140Call& c, uint64_t now_us);
  bool fun141(int ps, const Address& sr);  // false: invalid, code in R4060+ps
  void fun142(int ps, uint64_t now_us);    // PSOFF: stop the output (M1991 decides how)
  int64_t fun143(int ps) const;            // PSCNV: position in Ut

  // ---- control without a ladder FUN140 (ROS services and actions; lock held) ----
  // A table run by the unit itself on axis ps, as if by a FUN140 whose EN/PAU/ABT
  // are the commands below. False (with *why) if a ladder FUN140 holds the axis.
  bool load_table(int ps, const Table& t, std::string* why);
  enum class Command { Start, Pause, Resume, Abort };
  // Abort decelerates to P5 whatever M1991 says (an operator's stop).
  bool command(int ps, Command c, std::string* why);
  bool has_table(int ps) const;
  // State of the unit-run program: running, done (last step finished), error code.
  bool program_running(int ps) const;

  // The cell YAML's axes: section (names, output modes, simulated switches). Axes
  // with `output:` own their pins Y2n/Y2n+1; `wiring:` and `encoder:` become edge
  // sources of the counters (throws SourceError naming the YAML line if they clash).
  void configure(const AxesConfig& cfg);
  // The pins of axis ps (null unless configured with `output:`), docs/motion.md "Pulse pins".
  const AxisSignal* pins(int ps) const { return pins_[ps]; }
  const AxesConfig& config() const { return cfg_; }

  // ---- observation and control (lock held) ----
  const Axis& axis(int ps) const { return axes_[ps].axis; }
  const AxisParams& params(int ps) const { return axes_[ps].params; }
  void set_params(int ps, const AxisParams& p) { axes_[ps].params = p; }
  int64_t position(int ps) const { return axes_[ps].axis.position(now_ns_); }
  double frequency(int ps) const { return axes_[ps].axis.frequency(now_ns_); }
  int step(int ps) const;            // step being run (WR+0), 0 if none
  bool busy(int ps) const;           // a program holds the axis
  bool finished(int ps) const;       // M1996+ps
  int error(int ps) const;           // R4060+ps
  uint64_t now_ns() const { return now_ns_; }
  // ---- FUN147 / FUN148 (interpolation.h, mpg.h): they hold axes as a FUN140 does ----
  Interpolation& interpolation() { return *interp_; }
  Mpg& mpg() { return *mpg_; }
  uint32_t owner(int ps) const { return axes_[ps].owner; }  // UINT32_MAX: free (M1992+ps on)
  void take_axis(int ps, uint32_t owner) { axes_[ps].owner = owner; }
  void release_axis(int ps, uint32_t owner) {
    if (axes_[ps].owner == owner) axes_[ps].owner = UINT32_MAX;
  }
  Axis& drive(int ps) { return axes_[ps].axis; }
  void set_rest(int ps, int64_t rest) { axes_[ps].rest = rest; }  // DR4072 while idle
  // Every step completion, with its exact instant (tests, ROS feedback).
  using StepObserver = std::function<void(int ps, int step, uint64_t t_ns)>;
  void on_step_done(StepObserver f) { step_obs_.push_back(std::move(f)); }
  // Every DRVZ phase change at its instant: seek, to_limit, escape, creep, md1_stop,
  // md1_delay, md1_back, home (docs/motion.md "Homing"; `plc_cell sim --trace`).
  using HomeObserver = std::function<void(int ps, const char* phase, uint64_t t_ns)>;
  void on_home_phase(HomeObserver f) { home_obs_.push_back(std::move(f)); }

 private:
  enum class Phase { Idle, Moving, Waiting, SpeedWait, Paused, Stopping, Done, Homing };
  // DRVZ stages (docs/motion.md "Homing").
  enum class Home { Seek, ToLimit, Escape, Creep, Md1Stop, Md1Delay, Md1Back, Clr };
  struct Program {
    Fun140Call call;
    Table table;
    Phase phase = Phase::Idle;
    Phase after_stop = Phase::Idle;  // what a decelerated stop ends in
    int step = 0;                    // 1-based, the step being run
    uint64_t wait_until = kNever;    // WAIT Time / ACT deadline
    uint64_t act_deadline = kNever;
    bool chain = false;              // inside a DRVC chain: the next start keeps the speed
    double speed_hz = 0;
    int64_t paused_left = 0;         // logical pulses left at a pause / cut (DR4072)
    bool prev_en = false, prev_pau = false, prev_abt = false;
    bool dn = false, err = false;
    bool endless = false;
    Home home = Home::Seek;
    uint64_t t_cur = 0;              // the instant this program was last brought to
    uint64_t home_until = kNever;    // MD1 delay / CLR pulse end
    int pg0_count = 0;
    // Steps that completed at once (nothing to move) at instant empty_at: a GOTO loop of
    // such steps never lets time pass, so it is refused as advance()'s guard refuses it.
    uint64_t empty_at = kNever;
    int empty_steps = 0;
    bool counting = false, dog_seen = false, prev_pg0 = false;
    bool armed = true;               // EN was off since the last start
    bool external = false;           // run by load_table/command, no registers
    bool chain_forward = true;
    double chain_speed = 0;          // speed at the end of the previous DRVC section
    bool move_forward = true;
    int move_delta_sign = 1;
  };
  struct AxisState {
    Axis axis;
    AxisParams params;
    uint32_t owner = UINT32_MAX;  // FUN140 instance holding the axis
    bool finished = false;        // M1996+n
    int64_t written_pos = 0;      // DR4088 as last written, to see ladder writes
    int64_t rest = 0;             // DR4072 when idle: what a cut/stop left unsent
  };

  void advance(uint64_t t);
  void advance(Program& p, uint64_t t);
  uint64_t next_event(const Program& p) const;
  void step_done(Program& p, uint64_t t);
  void transfer(Program& p, uint64_t t);
  void go_to(Program& p, int target, uint64_t t);
  void start_step(Program& p, int k, uint64_t t);
  void start_move(Program& p, const Step& s, uint64_t t);
  void stop(Program& p, uint64_t t, Phase then, bool force_decel = false);
  void fail(Program& p, int code, uint64_t t);
  bool load(Program& p);
  bool contact(const Step& s) const;
  int32_t read32(Operand::Kind k, int32_t idx) const;
  uint16_t read16(Operand::Kind k, int32_t idx) const;
  uint16_t read_time(const Step& s) const;
  void write_status(uint64_t t);
  void adopt_ladder_positions();
  void preload();
  // Homing (DRVZ).
  void start_homing(Program& p, const Step& s, uint64_t t);
  void home_check(Program& p, uint64_t t);
  uint64_t home_next_event(const Program& p) const;
  void home_found(Program& p, uint64_t t);
  void set_home(Program& p, Home h, uint64_t t);  // and tells the observers
  void run_endless(Program& p, uint64_t t, int sign, double hz);
  bool input(int ps, int x, uint64_t t) const;  // positional switch level, else the X image
  void write_switches(uint64_t t);
  void write_wr(Program& p);
  // The speeds (Hz) and rates (Hz/s) of axis ps's FUN140 moves: FUN141's P4/P5/P8/P12,
  // or its `stepspeed:` form (step_speed.h), which replaces them.
  struct Ramp {
    double start, max, acc, dec;
  };
  Ramp ramp(int ps) const;
  // The `stepspeed:` completion relay of axis ps, if it has one.
  void set_done(int ps, bool on);

  Plc& plc_;
  ScanEngine& engine_;
  Memory& mem_;
  std::array<AxisState, kAxes> axes_;
  std::map<uint32_t, Program> programs_;  // by FUN140 instance
  uint64_t now_ns_ = 0;
  std::vector<StepObserver> step_obs_;
  std::vector<HomeObserver> home_obs_;
  AxesConfig cfg_;
  bool preloaded_ = false;                // the YAML's tables written since RUN
  void attach_signals();                  // pulse_pins.cpp: pins, wiring and encoders
  void detach_signals();
  void write_pins(uint64_t t);            // the Y image of owned pins shows their level at t

  timeline::Scheduler& sched_;
  hsc::HscUnit* hsc_ = nullptr;           // the counters' unit (pins, encoders, MPG counts), if any
  std::vector<std::unique_ptr<AxisSignal>> signals_;  // owned; the counters hold pointers
  std::array<const AxisSignal*, kAxes> pins_{};
  std::unique_ptr<Interpolation> interp_;
  std::unique_ptr<Mpg> mpg_;
};

}  // namespace motion
}  // namespace plc_cell
