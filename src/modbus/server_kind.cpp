#include "plc_cell/modbus/server_kind.h"

#include "plc_cell/modbus/slave_servers.h"

namespace plc_cell {
namespace modbus {

ServerKind server_kind() {
  ServerKind k;
  k.name = "modbus";
  k.title = "Modbus slave and gateway (docs/modbus.md)";
  SettingSpec s;
  s = {};
  s.key = "tcp", s.type = SettingType::HostPort;
  s.help = "HOST:PORT served as Modbus/TCP (the standard port is 502)";
  k.settings.push_back(s);
  s = {};
  s.key = "rtu", s.type = SettingType::SerialLine, s.format = "8E1";
  s.help = "DEVICE[:BAUD[:FORMAT]] served as Modbus RTU (default 9600 8E1)";
  k.settings.push_back(s);
  s = {};
  s.key = "id", s.type = SettingType::Integer, s.fallback = "1", s.lo = 1, s.hi = 247;
  s.help = "the RTU slave id, and the gateway's own unit id (1-247)";
  k.settings.push_back(s);
  s = {};
  s.key = "writable", s.type = SettingType::Writable, s.fallback = "all";
  s.help = "what clients may write: all, none, or ranges such as D0-D99,M800 (docs/security.md)";
  k.settings.push_back(s);
  s = {};
  s.key = "max_connections", s.type = SettingType::Integer, s.fallback = "16", s.lo = 1, s.hi = 1024;
  s.help = "open TCP connections at most; one more is refused";
  k.settings.push_back(s);
  s = {};
  s.key = "idle_timeout", s.type = SettingType::Duration, s.fallback = "60s", s.lo = 1000, s.hi = 86400000000;
  s.help = "a TCP connection silent this long is closed (1ms-24h)";
  k.settings.push_back(s);
  s = {};
  s.key = "gateway", s.type = SettingType::SerialLine, s.format = "8E1";
  s.help = "DEVICE[:BAUD[:FORMAT]]: the TCP server forwards other unit ids to RTU slaves on it";
  k.settings.push_back(s);
  s = {};
  s.key = "gateway_wait", s.type = SettingType::Duration, s.fallback = "150ms", s.lo = 1000, s.hi = 60000000;
  s.retired_ros = "modbus_gateway_wait_ms";
  s.help = "how long the gateway waits for each RTU answer (1ms-60s; a bare number is seconds)";
  k.settings.push_back(s);
  s = {};
  s.key = "gateway_retries", s.type = SettingType::Integer, s.fallback = "2", s.lo = 0, s.hi = 10;
  s.help = "attempts after the first before the gateway answers exception 0x0B";
  k.settings.push_back(s);
  k.make = [](Plc& plc, const Settings& v) {
    SlaveOptions o;
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
