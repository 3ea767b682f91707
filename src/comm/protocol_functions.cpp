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
  com_ports_ = std::static_pointer_cast<ComPorts>(ports_.back());
}

std::vector<ExtensionStatus> ProtocolFunctions::status(Plc&) const {
  std::vector<ExtensionStatus> out;
  if (!com_ports_) return out;
  for (int n : com_ports_->numbers()) {
    const std::shared_ptr<ComPort> p = com_ports_->get(n);
    ExtensionStatus s;
    s.name = "COM" + std::to_string(n);
    const bool up = p->line_up();
    const std::string error = p->last_error();
    s.level = up ? ExtensionStatus::Level::Ok : ExtensionStatus::Level::Warn;
    s.message = up ? "line open" : "line down: " + error;
    s.values = {{"line", p->line().to_string()},
                {"held by an instruction", p->holder() >= 0 ? "yes" : "no"},
                {"reopened", std::to_string(p->reopened())},
                {"last event", error}};
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace plc_cell
