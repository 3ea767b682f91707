#include "plc_cell/io/protocol_functions.h"

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"
#include "plc_cell/fatek/client.h"
#include "plc_cell/fatek/clink.h"
#include "plc_cell/io/serial_settings.h"
#include "plc_cell/modbus/fun150.h"

namespace plc_cell {
namespace {

// The keys of the two sections (their readers below take what they know and would
// silently pass over a misspelt key).
void check_keys(const CellConfig& cfg) {
  const YamlReader r(cfg.file);
  if (!cfg.document.IsMap()) return;
  if (const YAML::Node f = cfg.document["fatek"]) r.only(f, "fatek", {"ports", "timeout_ms"});
  if (const YAML::Node m = cfg.document["modbus"]) {
    r.only(m, "modbus", {"ports"});
    if (m["ports"] && m["ports"].IsMap())
      for (const auto& kv : m["ports"]) r.only(kv.second, "modbus.ports." + kv.first.as<std::string>(), {"tcp", "rtu"});
  }
}

// Runs the reading of the `fatek:` then the `modbus:` section; an error names the file
// and the section's line. *section says which one is being read.
template <typename F>
void in_sections(const CellConfig& cfg, const char** section, F&& read) {
  try {
    check_keys(cfg);
    read();
  } catch (const SourceError&) {
    throw;
  } catch (const std::exception& e) {
    const YAML::Node n = cfg.document[*section];
    const int line = n ? n.Mark().line + 1 : 0;
    throw SourceError::at(cfg.file, line, 0, std::string("section '") + *section + "': " + e.what());
  }
}

// The `fatek:` section as ClinkPorts::from_yaml reads it, step for step, so the same
// entries fail with the same messages; the transports are made (which parses their
// addresses) but never opened.
void check_clink_ports(const YAML::Node& f) {
  if (!f || !f["ports"]) return;
  if (f["timeout_ms"]) (void)f["timeout_ms"].as<int>();
  for (const auto& kv : f["ports"]) {
    const int n = kv.first.as<int>();
    const std::string where = kv.second.as<std::string>();
    if (where.rfind("tcp:", 0) == 0) (void)fatek::tcp_transport(where.substr(4));
    else (void)fatek::serial_transport(parse_serial_settings(where, "7E1"));
    if (n < 1 || n > 4) throw Error("FUN151 port " + std::to_string(n) + " outside 1..4");
  }
}

}  // namespace

std::vector<std::shared_ptr<void>> install_protocol_functions(const CellConfig& cfg, FunctionTable& t) {
  std::vector<std::shared_ptr<void>> keep;
  const char* section = "fatek";
  in_sections(cfg, &section, [&] {
    auto clink = fatek::ClinkPorts::from_yaml(cfg.document["fatek"]);
    fatek::add_clink_function(t, clink);
    keep.push_back(clink);
    section = "modbus";
    keep.push_back(modbus::add_fun150(t, modbus::parse_mbus_ports(cfg.document["modbus"])));
  });
  return keep;
}

std::vector<std::shared_ptr<void>> check_protocol_functions(const CellConfig& cfg, FunctionTable& t) {
  std::vector<std::shared_ptr<void>> keep;
  const char* section = "fatek";
  in_sections(cfg, &section, [&] {
    check_clink_ports(cfg.document["fatek"]);
    auto clink = std::make_shared<fatek::ClinkPorts>();  // no port: no line, no thread
    fatek::add_clink_function(t, clink);
    keep.push_back(clink);
    section = "modbus";
    (void)modbus::parse_mbus_ports(cfg.document["modbus"]);
    keep.push_back(modbus::add_fun150(t, {}));
  });
  return keep;
}

}  // namespace plc_cell
