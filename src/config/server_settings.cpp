#include "plc_cell/config/server_settings.h"

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/writable_ranges.h"

namespace plc_cell {
namespace {

// "60s", "500ms" or a number of seconds.
int timeout_ms(const YamlReader& r, const YAML::Node& n, const std::string& key) {
  try {
    const uint64_t us = parse_duration_us(r.str(n, key));
    if (us >= 1000 && us <= 86400000000ull) return int(us / 1000);
  } catch (const Error&) {
  }
  r.fail(n, key, "expected a duration between 1ms and 24h, e.g. 60s");
}

// "D0-D99, M800" or a list [D0-D99, M800]; checked here so the error names the line.
std::string ranges(const YamlReader& r, const YAML::Node& n, const std::string& key) {
  std::string s;
  if (n.IsSequence()) {
    for (size_t i = 0; i < n.size(); ++i) s += (s.empty() ? "" : ",") + r.str(n[i], key);
    if (s.empty()) s = "none";
  } else {
    s = r.str(n, key);
  }
  try {
    WritableRanges::parse(s);
  } catch (const Error& e) {
    r.fail(n, key, e.what());
  }
  return s;
}

}  // namespace

ServerSettings parse_server_settings(const CellConfig& cfg) {
  ServerSettings out;
  if (cfg.document.IsNull() || !cfg.document.IsMap()) return out;
  const YAML::Node s = cfg.document["servers"];
  if (!s) return out;
  const YamlReader r(cfg.file);
  r.only(s, "servers", {"fatek", "modbus"});
  if (const auto n = s["fatek"]) {
    r.only(n, "servers.fatek", {"tcp", "serial", "station", "writable", "max_connections", "idle_timeout"});
    auto& o = out.fatek;
    if (n["tcp"]) o.tcp = r.host_port(n["tcp"], "servers.fatek.tcp");
    if (n["serial"]) o.serial = r.serial_line(n["serial"], "servers.fatek.serial", "7E1");
    if (n["station"]) o.station = r.integer(n["station"], "servers.fatek.station", 1, 254);
    if (n["writable"]) o.writable = ranges(r, n["writable"], "servers.fatek.writable");
    if (n["max_connections"]) o.max_connections = r.integer(n["max_connections"], "servers.fatek.max_connections", 1, 1024);
    if (n["idle_timeout"]) o.idle_timeout_ms = timeout_ms(r, n["idle_timeout"], "servers.fatek.idle_timeout");
  }
  if (const auto n = s["modbus"]) {
    r.only(n, "servers.modbus", {"tcp", "rtu", "id", "writable", "max_connections", "idle_timeout"});
    auto& o = out.modbus;
    if (n["tcp"]) o.tcp = r.host_port(n["tcp"], "servers.modbus.tcp");
    if (n["rtu"]) o.rtu = r.serial_line(n["rtu"], "servers.modbus.rtu", "8E1");
    if (n["id"]) o.id = r.integer(n["id"], "servers.modbus.id", 1, 247);
    if (n["writable"]) o.writable = ranges(r, n["writable"], "servers.modbus.writable");
    if (n["max_connections"]) o.max_connections = r.integer(n["max_connections"], "servers.modbus.max_connections", 1, 1024);
    if (n["idle_timeout"]) o.idle_timeout_ms = timeout_ms(r, n["idle_timeout"], "servers.modbus.idle_timeout");
  }
  return out;
}

}  // namespace plc_cell
