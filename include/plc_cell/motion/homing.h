#pragma once
// The homing component: a FUN140 DRVZ step (zero return) in virtual time, stage by
// stage (docs/motion.md "Homing"): seek the DOG, creep, count PG0 or leave the DOG
// (MD0/MD1/MD2), the CLR pulse; the switches' edges are found as instants of the
// closed-form move, so each stage changes at its exact instant.
#include <cstdint>
#include <functional>
#include <vector>

#include "plc_cell/motion/axis_state.h"
#include "plc_cell/motion/program.h"

namespace plc_cell {

class Memory;

namespace motion {

struct AxesConfig;
class Ramps;
class Switches;

class Homing {
 public:
  // Every stage change at its instant: seek, to_limit, escape, creep, md1_stop,
  // md1_delay, md1_back, home.
  using Observer = std::function<void(int ps, const char* phase, uint64_t t_ns)>;

  Homing(Memory& mem, AxisStates& axes, const AxesConfig& cfg, const Ramps& ramps, const Switches& switches)
      : mem_(mem), axes_(axes), cfg_(cfg), ramps_(ramps), switches_(switches) {}

  // Starts step s of p at t at the program's speed: 0, then check() at t, or the error
  // code (50-53) of a bad zero mode or parameter.
  int start(Program& p, const Step& s, uint64_t t);
  // Looks at the inputs at t and goes on to the next stage if they say so; true once
  // the home position is set (the caller completes the step).
  bool check(Program& p, uint64_t t);
  // The next instant a stage can change (a switch edge, the MD1 delay, the CLR pulse).
  uint64_t next_event(const Program& p) const;
  // WR+1 "waiting": the MD1 delay or the CLR pulse.
  static bool waiting(const Program& p) {
    return p.phase == Phase::Homing && (p.home.stage == Home::Md1Delay || p.home.stage == Home::Clr);
  }
  void on_phase(Observer f) { obs_.push_back(std::move(f)); }

 private:
  bool found(Program& p, uint64_t t);
  void set(Program& p, Home h, uint64_t t);  // and tells the observers
  void run_endless(Program& p, uint64_t t, int sign, double hz);
  bool seek(Program& p, const Step& s, uint64_t t, bool dog, bool limit, bool pg0);
  bool creep(Program& p, const Step& s, uint64_t t, bool dog, bool pg0);
  bool clear(Program& p, uint64_t t);

  Memory& mem_;
  AxisStates& axes_;
  const AxesConfig& cfg_;
  const Ramps& ramps_;
  const Switches& switches_;
  std::vector<Observer> obs_;
};

}  // namespace motion
}  // namespace plc_cell
