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
  // Input x is a capture input: a pulse between two scans is seen ON at the next scan.
  void capture(uint32_t x) { captured_.push_back(x); }
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
  std::vector<uint32_t> captured_;
  bool scanned_ = false;
  uint64_t last_us_ = 0;  // the previous scan
};

}  // namespace plc_cell
