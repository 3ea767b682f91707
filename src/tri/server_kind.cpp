#include "plc_cell/tri/server_kind.h"

#include "plc_cell/tri/client.h"
#include "plc_cell/tri/server.h"

namespace plc_cell {
namespace tri {

ServerKind server_kind() {
  ServerKind k;
  k.name = "tri";
  k.title = "TRi host-link slave (docs/tri.md)";
  k.settings = {
      setting("tcp", SettingType::HostPort, "HOST:PORT served over TCP (the FMD's FServer port is 9080); repeatable"),
      serial_setting("serial", "8N1", "DEVICE[:BAUD[:FORMAT]] served over a serial line (default 38400 8N1); repeatable"),
      integer_setting("id", 1, 0, 255, "device ID multi-point frames carry (0-255, written 00-FF on the wire)"),
      integer_setting("wildcard_fcs", 1, 0, 1, "1: accept the wildcard FCS 00 (AUTO mode); 0: refuse it (SETPROTOCOL n,5)")};
  k.settings[0].repeatable = k.settings[1].repeatable = true;
  for (auto& s : client_limits(6)) k.settings.push_back(s);  // the FMD's 6 TCP connections
  k.make = [](const ServerContext& c, const Settings& v) {
    Plc& plc = c.plc;
    ServerOptions o;
    o.id = int(v.integer("id"));
    o.wildcard_fcs = v.integer("wildcard_fcs") != 0;
    o.writable = v.writable("writable");
    o.max_connections = int(v.integer("max_connections"));
    o.idle_timeout_ms = int(v.duration_us("idle_timeout") / 1000);
    std::vector<std::unique_ptr<Server>> out;
    for (const auto& hp : v.all("tcp")) {
      std::string host;
      int port = 0;
      parse_host_port(hp, &host, &port);
      out.push_back(std::make_unique<TcpServer>(plc, host, port, o));
    }
    for (const auto& dev : v.all("serial"))
      out.push_back(std::make_unique<SerialServer>(plc, parse_serial_settings(dev, "8N1", kDefaultBaud), o));
    return out;
  };
  return k;
}

}  // namespace tri
}  // namespace plc_cell
