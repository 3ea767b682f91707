#pragma once
// A soft PLC with its cell config and simulated inputs: what `plc_cell sim/run`
// and plc_node both start from.
#include <memory>
#include <string>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/sim/simulated_cell.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {

class SoftCell {
 public:
  // config_path may be empty (no signals, no simulation); program_path overrides the
  // config's cell.program. Throws SourceError/Error with file and line on bad input.
  SoftCell(const std::string& config_path, const std::string& program_path);
  // The instruction set of every cell: the core's plus the subsystems' FUNs.
  static FunctionTable functions();
  ~SoftCell();

  Plc& plc() { return plc_; }
  // Only touch it under plc().locked(): the scan calls into it.
  SimulatedCell& simulation() { return *sim_; }
  const CellConfig& config() const { return config_; }
  const std::string& program_path() const { return program_path_; }
  // The temperature modules and thermal plants of `modules:`, or nullptr.
  temp::TemperatureCell* temperature() { return temperature_.get(); }

 private:
  CellConfig config_;
  std::string program_path_;
  Plc plc_;
  std::unique_ptr<SimulatedCell> sim_;
  std::unique_ptr<temp::TemperatureCell> temperature_;
};

}  // namespace plc_cell
