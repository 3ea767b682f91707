#include "plc_cell/fatek/server_kind.h"

#include "plc_cell/fatek/server.h"

namespace plc_cell {
namespace fatek {

ServerKind server_kind() {
  ServerKind k;
  k.name = "fatek";
  k.title = "FATEK slave (docs/fatek.md)";
  SettingSpec s;
  s = {};
  s.key = "tcp", s.type = SettingType::HostPort, s.repeatable = true;
  s.help = "HOST:PORT served over TCP (FATEK's default port is 500); repeatable";
  k.settings.push_back(s);
  s = {};
  s.key = "serial", s.type = SettingType::SerialLine, s.format = "7E1", s.repeatable = true;
  s.help = "DEVICE[:BAUD[:FORMAT]] served over a serial line (default 9600 7E1); repeatable";
  k.settings.push_back(s);
  s = {};
  s.key = "station", s.type = SettingType::Integer, s.fallback = "1", s.lo = 1, s.hi = 254, s.cli_alias = "station";
  s.help = "station number the servers answer (1-254)";
  k.settings.push_back(s);
  s = {};
  s.key = "writable", s.type = SettingType::Writable, s.fallback = "all";
  s.help = "what clients may write: all, none, or ranges such as D0-D99,M800 (docs/security.md)";
  k.settings.push_back(s);
  s = {};
  s.key = "max_connections", s.type = SettingType::Integer, s.fallback = "8", s.lo = 1, s.hi = 1024;
  s.help = "open TCP connections at most; one more is refused";
  k.settings.push_back(s);
  s = {};
  s.key = "idle_timeout", s.type = SettingType::Duration, s.fallback = "60s", s.lo = 1000, s.hi = 86400000000;
  s.help = "a TCP connection silent this long is closed (1ms-24h)";
  k.settings.push_back(s);
  k.make = [](Plc& plc, const Settings& v) {
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
