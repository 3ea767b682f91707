#pragma once
// The simulated cell: drives input terminals from InputSignals before every scan.
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/scan_engine.h"
#include "plc_cell/sim/input_signal.h"

namespace plc_cell {

class SimulatedCell : public ScanHook {
 public:
  SimulatedCell(ScanEngine& engine, const Memory& mem) : engine_(engine), mem_(mem) {}

  void drive(uint32_t x, std::unique_ptr<InputSignal> signal);
  // Stops simulating input x (something else, e.g. a ROS topic, now drives it).
  void release(uint32_t x);
  void before_inputs(uint64_t now_us) override;
  bool empty() const { return drivers_.empty(); }

 private:
  struct Driver {
    uint32_t x;
    std::unique_ptr<InputSignal> signal;
  };
  ScanEngine& engine_;
  const Memory& mem_;
  std::vector<Driver> drivers_;
};

}  // namespace plc_cell
