#include "plc_cell/fatek/server_kind.h"

#include "plc_cell/fatek/server.h"

namespace plc_cell {
namespace fatek {

ServerKind server_kind() {
  ServerKind k;
  k.name = "fatek";
  k.title = "FATEK slave (docs/fatek.md)";
  k.settings = {setting("tcp", SettingType::HostPort, "HOST:PORT served over TCP (FATEK's default port is 500); repeatable"),
                serial_setting("serial", "7E1", "DEVICE[:BAUD[:FORMAT]] served over a serial line (default 9600 7E1); repeatable"),
                integer_setting("station", 1, 1, 254, "station number the servers answer (1-254)")};
  k.settings[0].repeatable = k.settings[1].repeatable = true;
  k.settings[2].cli_alias = "station";
  for (auto& s : client_limits(8)) k.settings.push_back(s);  // as the FATEK Ethernet module
  k.make = [](const ServerContext& c, const Settings& v) {
    Plc& plc = c.plc;
    ServerPolicy p;
    p.writable = v.writable("writable");
    p.max_connections = int(v.integer("max_connections"));
    p.idle_timeout_ms = int(v.duration_us("idle_timeout") / 1000);
    const int station = int(v.integer("station"));
    std::vector<std::unique_ptr<Server>> out;
    for (const auto& hp : v.all("tcp")) out.push_back(make_tcp_server(plc, hp, station, p));
    for (const auto& dev : v.all("serial")) out.push_back(make_serial_server(plc, dev, station, p));
    return out;
  };
  return k;
}

}  // namespace fatek
}  // namespace plc_cell
