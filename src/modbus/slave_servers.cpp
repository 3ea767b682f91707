#include "plc_cell/modbus/slave_servers.h"

#include "plc_cell/core/error.h"
#include "plc_cell/io/serial_settings.h"
#include "plc_cell/modbus/gateway.h"
#include "plc_cell/modbus/rtu_server.h"
#include "plc_cell/modbus/tcp_server.h"

namespace plc_cell {
namespace modbus {

std::vector<std::unique_ptr<Server>> make_slave_servers(Plc& plc, const SlaveOptions& o) {
  std::vector<std::unique_ptr<Server>> out;
  if (!o.tcp.empty()) {
    TcpServerOptions t;
    parse_host_port(o.tcp, &t.host, &t.port);
    t.max_connections = o.max_connections;
    t.idle_timeout_ms = o.idle_timeout_ms;
    t.writable = o.writable;
    t.map = o.map;
    if (o.max_connections < 1) throw Error("Modbus TCP: max connections must be at least 1");
    if (o.idle_timeout_ms < 1) throw Error("Modbus TCP: idle timeout must be positive");
    if (o.gateway.empty()) {
      out.push_back(std::make_unique<TcpServer>(plc, t));
    } else {
      GatewayOptions g;
      g.tcp = t;
      g.tcp.own_unit = o.id;
      g.line = parse_serial_settings(o.gateway, "8E1");
      g.wait_ms = o.gateway_wait_ms;
      g.retries = o.gateway_retries;
      out.push_back(std::make_unique<GatewayServer>(plc, g));
    }
  } else if (!o.gateway.empty()) {
    throw Error("Modbus gateway " + o.gateway + ": needs a Modbus/TCP endpoint too");
  }
  if (!o.rtu.empty())
    out.push_back(std::make_unique<RtuServer>(plc, parse_serial_settings(o.rtu, "8E1"), o.id, o.writable, *o.map));
  return out;
}

}  // namespace modbus
}  // namespace plc_cell
