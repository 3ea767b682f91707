#pragma once
// The positioning component: the FUN140 programs on the axes, each a table run step by
// step in virtual time (docs/motion.md "FUN140"). Each program is advanced from event
// to event (move ends, WAIT/ACT times) up to an instant, starting the next steps at the
// exact instants; contacts (WAIT Xn, EXT Xn) and EN/PAU/ABT are seen at the scans.
// A table may also be run without a ladder FUN140 (load_table/command: ROS).
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "plc_cell/motion/axis_state.h"
#include "plc_cell/motion/program.h"

namespace plc_cell {

class Memory;
namespace timeline {
class Scheduler;
}

namespace motion {

struct AxesConfig;
class Homing;
class Ramps;
class StatusRegisters;
class Switches;

enum class ProgramCommand { Start, Pause, Resume, Abort };

class Positioning {
 public:
  struct Parts {
    Memory& mem;
    timeline::Scheduler& sched;  // PSOnI is raised there at each step's end
    AxisStates& axes;
    const uint64_t& now_ns;      // the unit's instant
    const Ramps& ramps;
    Homing& homing;
    StatusRegisters& status;
    const Switches& switches;
  };
  explicit Positioning(const Parts& parts) : x_(parts) {}

  // ---- FUN140 (lock held) ----
  Fun140Outputs fun140(const Fun140Call& c, uint64_t now_us);
  // The programs run without a ladder FUN140, as if their FUN140 ran now.
  void run_unit_programs(uint64_t now_us);
  // FUN142 PSOFF: the programs on axis ps stop (M1991 decides how).
  void psoff(int ps, uint64_t t);
  void advance(uint64_t t);  // every program, event by event
  uint64_t next_event_ns() const;
  void on_stop() { programs_.clear(); }
  bool idle() const { return programs_.empty(); }  // no FUN140 or unit-run table to advance

  // ---- a table run without a ladder FUN140 (unit_programs.cpp) ----
  bool load_table(int ps, const Table& t, std::string* why);
  bool command(int ps, ProgramCommand c, std::string* why);
  bool has_table(int ps) const;
  bool program_running(int ps) const;

  int step(int ps) const;  // step being run (WR+0), 0 if none
  using StepObserver = std::function<void(int ps, int step, uint64_t t_ns)>;
  void on_step_done(StepObserver f) { step_obs_.push_back(std::move(f)); }

 private:
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
  void write_wr(Program& p);
  void home_check(Program& p, uint64_t t);  // and completes the DRVZ step once home
  void finish_step(Program& p, uint64_t t);  // the move is complete: DN, PSOnI, transfer
  uint16_t read_time(const Step& s) const;
  // fun140.cpp: what EN/PAU/ABT and the scan ask of a program.
  void enable(Program& p, const Fun140Call& c, uint64_t t);
  void resume(Program& p, const Fun140Call& c, uint64_t t);
  void follow(Program& p, const Fun140Call& c, uint64_t t);  // a move in progress

  Parts x_;
  std::map<uint32_t, Program> programs_;  // by FUN140 instance
  std::vector<StepObserver> step_obs_;
};

}  // namespace motion
}  // namespace plc_cell
