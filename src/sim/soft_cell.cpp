#include "plc_cell/sim/soft_cell.h"

#include "plc_cell/core/error.h"
#include "plc_cell/hsc/hsc_unit.h"

namespace plc_cell {

SoftCell::SoftCell(const std::string& config_path, const std::string& program_path) {
  if (!config_path.empty()) config_ = load_cell_config(config_path);
  program_path_ = program_path.empty() ? config_.program : program_path;
  if (program_path_.empty())
    throw Error("no program: give --program or set cell.program in the cell config");
  sim_ = plc_.locked([&](ScanEngine& e, Memory& m) { return std::make_unique<SimulatedCell>(e, m); });
  apply_cell_config(config_, plc_, *sim_);
  plc_.locked([&](ScanEngine& e, Memory&) {
    e.add_hook(sim_.get());
    return 0;
  });
  const YAML::Node& doc = config_.document;
  hsc_ = std::make_unique<hsc::HscUnit>(plc_, hsc::parse_hsc_config(doc["counters"], config_.file));
  plc_.load_program_file(program_path_);
}

SoftCell::~SoftCell() {
  hsc_.reset();
  plc_.locked([&](ScanEngine& e, Memory&) {
    e.remove_hook(sim_.get());
    return 0;
  });
}

}  // namespace plc_cell
