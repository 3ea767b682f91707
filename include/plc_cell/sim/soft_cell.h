#pragma once
// A soft PLC with its cell config and simulated inputs: the one way a cell is built.
// `plc_cell sim`, `run` and `check` and plc_node all construct a SoftCell, so what one of
// them rejects every one rejects, with the same messages. Building starts nothing: no
// thread, no port, no server (the installer decides about FUN150/151's ports).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/error_list.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/sim/simulated_cell.h"
#include "plc_cell/temp/pwmda.h"
#include "plc_cell/temp/rtc.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {

namespace hsc {
class HscUnit;
}
namespace motion {
class MotionUnit;
}

// Adds FUN instructions that need the cell's config (FUN150/151 and their ports) before
// the program is parsed. What it returns (port threads, engines) lives as long as the cell.
using CellFunctionInstaller =
    std::function<std::vector<std::shared_ptr<void>>(const CellConfig&, FunctionTable&)>;

// A section of the cell YAML that a layer above the simulation reads (the protocol
// servers' `servers:`): read with the other sections, so its errors are listed with theirs.
struct CellSection {
  std::string name;
  std::function<void(const CellConfig&)> read;  // throws plc_cell::Error or SourceError
};

class SoftCell {
 public:
  // config_path may be empty (no signals, no simulation); program_path overrides the
  // config's cell.program. Every section of the config is read even when an earlier one
  // failed, then the program (when the sections that make its instruction set are
  // sound); one SourceError lists every error found, each with file:line:column.
  // A config or program that cannot be opened, or "no program", throws at once.
  SoftCell(const std::string& config_path, const std::string& program_path,
           const CellFunctionInstaller& install = {}, const std::vector<CellSection>& sections = {});
  // The instruction set of a cell of generation g (modules.generation): the core's
  // plus the subsystems' FUNs.
  static FunctionTable functions(temp::Generation g = temp::Generation::FBs);
  ~SoftCell();

  Plc& plc() { return plc_; }
  // Only touch it under plc().locked(): the scan calls into it.
  SimulatedCell& simulation() { return *sim_; }
  const CellConfig& config() const { return config_; }
  // High-speed counters, timers and interrupts (the config's counters: section).
  // Only touch it under plc().locked().
  hsc::HscUnit& counters() { return *hsc_; }
  // Pulse-output axes PSO0-PSO3 and FUN140 programs. Only touch it under plc().locked().
  motion::MotionUnit& motion() { return *motion_; }
  const std::string& program_path() const { return program_path_; }
  // The temperature modules and thermal plants of `modules:`, or nullptr.
  temp::TemperatureCell* temperature() { return temperature_.get(); }
  temp::Rtc* rtc() { return rtc_.get(); }
  temp::PwmdaOutputs* pwmda() { return pwmda_.get(); }

 private:
  static FunctionTable functions_for(const CellConfig& cfg, const CellFunctionInstaller& install,
                                     std::vector<std::shared_ptr<void>>* keep, ErrorList* errors, bool* complete);
  void build(const std::string& program_path, const std::vector<CellSection>& sections);
  void release();  // hooks off the engine, port owners first

  ErrorList errors_;           // while building; before config_, which fills it
  bool functions_complete_ = true;  // modules.generation, fatek: and modbus: were read
  CellConfig config_;
  std::vector<std::shared_ptr<void>> installed_;  // released first: ports stop before the PLC goes
  std::string program_path_;
  Plc plc_;
  std::unique_ptr<SimulatedCell> sim_;
  std::unique_ptr<hsc::HscUnit> hsc_;  // after sim_: its hook sees the simulated inputs
  std::unique_ptr<temp::TemperatureCell> temperature_;
  std::unique_ptr<temp::Rtc> rtc_;
  std::unique_ptr<temp::PwmdaOutputs> pwmda_;  // nullptr without modules.pwmda
  std::unique_ptr<motion::MotionUnit> motion_;
};

}  // namespace plc_cell
