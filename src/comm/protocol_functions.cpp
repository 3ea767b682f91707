#include "plc_cell/comm/protocol_functions.h"

#include "plc_cell/core/error.h"
#include "plc_cell/fatek/clink.h"
#include "plc_cell/modbus/fun150.h"

namespace plc_cell {
namespace {

// Runs the reading of the `fatek:` then the `modbus:` section; an error names the file
// and the section's line. *section says which one is being read.
template <typename F>
void in_sections(const CellConfig& cfg, const char** section, F&& read) {
  try {
    read();
  } catch (const SourceError&) {
    throw;
  } catch (const std::exception& e) {
    const YAML::Node n = cfg.document[*section];
    const int line = n ? n.Mark().line + 1 : 0;
    throw SourceError::at(cfg.file, line, 0, std::string("section '") + *section + "': " + e.what());
  }
}

}  // namespace

std::vector<std::shared_ptr<void>> install_protocol_functions(const CellConfig& cfg, FunctionTable& t) {
  std::vector<std::shared_ptr<void>> keep;
  const char* section = "fatek";
  in_sections(cfg, &section, [&] {
    auto clink = fatek::ClinkPorts::from_yaml(cfg.document["fatek"], cfg.file);
    fatek::add_clink_function(t, clink);
    keep.push_back(clink);
    section = "modbus";
    keep.push_back(modbus::add_fun150(t, modbus::parse_mbus_ports(cfg.document["modbus"], cfg.file)));
  });
  return keep;
}

std::vector<std::shared_ptr<void>> check_protocol_functions(const CellConfig& cfg, FunctionTable& t) {
  std::vector<std::shared_ptr<void>> keep;
  const char* section = "fatek";
  in_sections(cfg, &section, [&] {
    (void)fatek::read_clink_settings(cfg.document["fatek"], cfg.file);  // what from_yaml reads, no line opened
    auto clink = std::make_shared<fatek::ClinkPorts>();  // no port: no line, no thread
    fatek::add_clink_function(t, clink);
    keep.push_back(clink);
    section = "modbus";
    (void)modbus::parse_mbus_ports(cfg.document["modbus"], cfg.file);
    keep.push_back(modbus::add_fun150(t, {}));
  });
  return keep;
}

void ProtocolFunctions::install(const CellConfig& cfg, FunctionTable& t) {
  ports_ = open_ports_ ? install_protocol_functions(cfg, t) : check_protocol_functions(cfg, t);
}

}  // namespace plc_cell
