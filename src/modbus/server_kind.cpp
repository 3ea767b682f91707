#include "plc_cell/modbus/server_kind.h"

#include "plc_cell/modbus/slave_servers.h"

namespace plc_cell {
namespace modbus {

ServerKind server_kind() {
  ServerKind k;
  k.name = "modbus";
  k.title = "Modbus slave and gateway (docs/modbus.md)";
  k.settings = {setting("tcp", SettingType::HostPort, "HOST:PORT served as Modbus/TCP (the standard port is 502)"),
                serial_setting("rtu", "8E1", "DEVICE[:BAUD[:FORMAT]] served as Modbus RTU (default 9600 8E1)"),
                integer_setting("id", 1, 1, 247, "the RTU slave id, and the gateway's own unit id (1-247)")};
  for (auto& s : client_limits(16)) k.settings.push_back(s);
  k.settings.push_back(
      serial_setting("gateway", "8E1", "DEVICE[:BAUD[:FORMAT]]: the TCP server forwards other unit ids to RTU slaves on it"));
  k.settings.push_back(duration_setting("gateway_wait", "150ms", 1000, 60000000,
                                        "how long the gateway waits for each RTU answer (1ms-60s; a bare number is seconds)"));
  k.settings.back().retired_ros = "modbus_gateway_wait_ms";
  k.settings.push_back(
      integer_setting("gateway_retries", 2, 0, 10, "attempts after the first before the gateway answers exception 0x0B"));
  k.settings.push_back(setting("map", SettingType::Text,
                               "the map served: fbs (the FBs manual's) or tri (the TRi FMD's Table 14.1, docs/tri.md)", "fbs"));
  k.make = [](const ServerContext& c, const Settings& v) {
    Plc& plc = c.plc;
    SlaveOptions o;
    o.map = &map_profile(v.text("map"));  // the strategy, chosen once
    o.tcp = v.text("tcp");
    o.rtu = v.text("rtu");
    o.id = int(v.integer("id"));
    o.writable = v.writable("writable");
    o.max_connections = int(v.integer("max_connections"));
    o.idle_timeout_ms = int(v.duration_us("idle_timeout") / 1000);
    o.gateway = v.text("gateway");
    o.gateway_wait_ms = int(v.duration_us("gateway_wait") / 1000);
    o.gateway_retries = int(v.integer("gateway_retries"));
    return make_slave_servers(plc, o);
  };
  return k;
}

}  // namespace modbus
}  // namespace plc_cell
