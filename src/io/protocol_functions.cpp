#include "plc_cell/io/protocol_functions.h"

#include "plc_cell/core/error.h"
#include "plc_cell/fatek/clink.h"
#include "plc_cell/modbus/fun150.h"

namespace plc_cell {

std::vector<std::shared_ptr<void>> install_protocol_functions(const CellConfig& cfg, FunctionTable& t) {
  std::vector<std::shared_ptr<void>> keep;
  const char* section = "fatek";
  try {
    auto clink = fatek::ClinkPorts::from_yaml(cfg.document["fatek"]);
    fatek::add_clink_function(t, clink);
    keep.push_back(clink);
    section = "modbus";
    keep.push_back(modbus::add_fun150(t, modbus::parse_mbus_ports(cfg.document["modbus"])));
  } catch (const SourceError&) {
    throw;
  } catch (const std::exception& e) {
    const YAML::Node n = cfg.document[section];
    const int line = n ? n.Mark().line + 1 : 0;
    throw SourceError::at(cfg.file, line, 0, std::string("section '") + section + "': " + e.what());
  }
  return keep;
}

}  // namespace plc_cell
