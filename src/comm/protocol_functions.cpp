#include "plc_cell/comm/protocol_functions.h"

#include "plc_cell/comm/port_config.h"
#include "plc_cell/core/error.h"
#include "plc_cell/fatek/clink.h"
#include "plc_cell/io/com_ports.h"
#include "plc_cell/modbus/fun150.h"

namespace plc_cell {
namespace {

// FUN151 and FUN150 on the same ports: a port both use is one ComPort, one line.
std::vector<std::shared_ptr<void>> install(const CellConfig& cfg, FunctionTable& t, bool open_ports) {
  const PortSettings s = read_port_settings(cfg.document, cfg.file);
  // Checking opens nothing: the FUNs are there, with no port behind them.
  auto ports = open_ports ? std::make_shared<ComPorts>(s.lines) : std::make_shared<ComPorts>();
  auto clink = fatek::ClinkPorts::on(*ports, s.timeout_ms);
  fatek::add_clink_function(t, clink);
  auto engine = modbus::add_fun150_on(t, *ports);
  return {clink, engine, ports};
}

}  // namespace

std::vector<std::shared_ptr<void>> install_protocol_functions(const CellConfig& cfg, FunctionTable& t) {
  return install(cfg, t, true);
}

std::vector<std::shared_ptr<void>> check_protocol_functions(const CellConfig& cfg, FunctionTable& t) {
  return install(cfg, t, false);
}

void ProtocolFunctions::install(const CellConfig& cfg, FunctionTable& t) {
  ports_ = open_ports_ ? install_protocol_functions(cfg, t) : check_protocol_functions(cfg, t);
}

}  // namespace plc_cell
