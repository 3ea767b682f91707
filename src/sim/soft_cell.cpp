#include "plc_cell/sim/soft_cell.h"

#include "plc_cell/core/error.h"
#include "plc_cell/temp/temp_functions.h"

namespace plc_cell {

FunctionTable SoftCell::functions() {
  FunctionTable t = FunctionTable::with_core_functions();
  temp::add_temperature_functions(t);  // FUN86 TPCTL, FUN30 PID
  return t;
}

SoftCell::SoftCell(const std::string& config_path, const std::string& program_path) : plc_(functions()) {
  if (!config_path.empty()) config_ = load_cell_config(config_path);
  program_path_ = program_path.empty() ? config_.program : program_path;
  if (program_path_.empty())
    throw Error("no program: give --program or set cell.program in the cell config");
  sim_ = plc_.locked([&](ScanEngine& e, Memory& m) { return std::make_unique<SimulatedCell>(e, m); });
  apply_cell_config(config_, plc_, *sim_);
  plc_.locked([&](ScanEngine& e, Memory& m) {
    e.add_hook(sim_.get());
    temperature_ = temp::make_temperature_cell(config_.document, config_.file, m);
    if (temperature_) e.add_hook(temperature_.get());
    return 0;
  });
  plc_.load_program_file(program_path_);
}

SoftCell::~SoftCell() {
  plc_.locked([&](ScanEngine& e, Memory&) {
    e.remove_hook(sim_.get());
    if (temperature_) e.remove_hook(temperature_.get());
    return 0;
  });
}

}  // namespace plc_cell
