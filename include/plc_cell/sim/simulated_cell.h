#pragma once
// The simulated cell: drives input terminals from InputSignals before every scan.
#include <bitset>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/scan_engine.h"
#include "plc_cell/sim/input_signal.h"

namespace plc_cell {

namespace hsc {
class HscUnit;
}

class SimulatedCell final : public ScanHook {
 public:
  SimulatedCell(ScanEngine& engine, const Memory& mem) : engine_(engine), mem_(mem) {}

  void drive(uint32_t x, std::unique_ptr<InputSignal> signal);
  // The counter unit plays the signals of X0-X15 it was given as exact edges; this cell
  // stops sampling x (drop) and mutes the unit's edges with its own overrides.
  void exact_edges(hsc::HscUnit* unit) { exact_ = unit; }
  void drop(uint32_t x);
  // Input x played at exact instants from outside the cell's YAML (a wire of a line of
  // cells): on X0-X15, where the counter unit plays the simulation's steps, each edge
  // reaches the terminal (and a counter or an edge interrupt) at its instant, muted as the
  // simulation's are by override_input. exact(x) is false elsewhere (X16 and up, a pin an
  // analytic source drives, a cell with no counter unit): sample the input at the scans
  // with drive() instead.
  bool exact(uint32_t x) const;
  void schedule_edge(uint32_t x, uint64_t t_ns, bool level);
  // Something else (a scenario's set, a ROS topic) plays input x from now on: no later
  // level or edge of the simulation reaches it, until resume(x).
  void override_input(uint32_t x);
  // The simulation plays x again, from the level it gives now. False if it has no signal on x.
  bool resume(uint32_t x);
  bool simulates(uint32_t x) const;
  // Plays the same inputs as other from now on (a lockstep twin, sim/lockstep_cells.h):
  // what other's player overrides, this one does too, and what other resumed, this one resumes.
  void follow(const SimulatedCell& other);
  std::vector<uint32_t> simulated_inputs() const;  // in address order
  // Input x is a capture input: a pulse between two scans is seen ON at the next scan.
  void capture(uint32_t x) { captured_.push_back(x); }
  void before_inputs(uint64_t now_us) override;
  bool empty() const { return drivers_.empty(); }

 private:
  struct Driver {
    uint32_t x;
    std::unique_ptr<InputSignal> signal;
    bool overridden = false;  // still evaluated (a follow keeps its delays), not applied
  };
  ScanEngine& engine_;
  const Memory& mem_;
  hsc::HscUnit* exact_ = nullptr;
  std::vector<Driver> drivers_;
  std::vector<uint32_t> captured_;
  std::bitset<256> overridden_;  // override_input, until resume
  uint64_t overrides_ = 0;       // changes of overridden_, which follow() compares first
  uint64_t followed_ = 0;        // the other's overrides_ this one has followed
  bool scanned_ = false;
  uint64_t last_us_ = 0;  // the previous scan
};

}  // namespace plc_cell
