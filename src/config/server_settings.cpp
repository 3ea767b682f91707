#include "plc_cell/config/server_settings.h"

#include <set>

#include "plc_cell/core/error.h"
#include "plc_cell/core/writable_ranges.h"
#include "plc_cell/io/serial_settings.h"

namespace plc_cell {
namespace {

[[noreturn]] void fail(const std::string& file, const YAML::Node& n, const std::string& key, const std::string& msg) {
  const YAML::Mark m = n.Mark();
  throw SourceError::at(file, m.line >= 0 ? m.line + 1 : 0, m.column >= 0 ? m.column + 1 : 0, "key '" + key + "': " + msg);
}

void only(const std::string& file, const YAML::Node& map, const std::string& key, const std::set<std::string>& allowed) {
  if (!map.IsMap()) fail(file, map, key, "expected a mapping");
  for (const auto& kv : map) {
    const std::string k = kv.first.as<std::string>();
    if (allowed.count(k)) continue;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    fail(file, kv.first, key + "." + k, "unknown key (expected one of: " + list + ")");
  }
}

std::string text(const std::string& file, const YAML::Node& n, const std::string& key) {
  if (!n.IsScalar()) fail(file, n, key, "expected a single value");
  return n.as<std::string>();
}

int integer(const std::string& file, const YAML::Node& n, const std::string& key, int lo, int hi) {
  int v = 0;
  try {
    v = n.as<int>();
  } catch (const YAML::Exception&) {
    fail(file, n, key, "expected a whole number");
  }
  if (v < lo || v > hi) fail(file, n, key, "value out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v;
}

// "60s", "500ms" or a number of seconds.
int timeout_ms(const std::string& file, const YAML::Node& n, const std::string& key) {
  try {
    const uint64_t us = parse_duration_us(text(file, n, key));
    if (us >= 1000 && us <= 86400000000ull) return int(us / 1000);
  } catch (const Error&) {
  }
  fail(file, n, key, "expected a duration between 1ms and 24h, e.g. 60s");
}

// "D0-D99, M800" or a list [D0-D99, M800]; checked here so the error names the line.
std::string ranges(const std::string& file, const YAML::Node& n, const std::string& key) {
  std::string s;
  if (n.IsSequence()) {
    for (size_t i = 0; i < n.size(); ++i) s += (s.empty() ? "" : ",") + text(file, n[i], key);
    if (s.empty()) s = "none";
  } else {
    s = text(file, n, key);
  }
  try {
    WritableRanges::parse(s);
  } catch (const Error& e) {
    fail(file, n, key, e.what());
  }
  return s;
}

// Where a server listens, checked here so a bad one is a config error with its line, not a
// failure when the server starts.
std::string host_port(const std::string& file, const YAML::Node& n, const std::string& key) {
  const std::string v = text(file, n, key);
  try {
    std::string host;
    int port = 0;
    parse_host_port(v, &host, &port);
  } catch (const Error& e) {
    fail(file, n, key, e.what());
  }
  return v;
}

std::string serial_line(const std::string& file, const YAML::Node& n, const std::string& key, const char* format) {
  const std::string v = text(file, n, key);
  try {
    parse_serial_settings(v, format);
  } catch (const Error& e) {
    fail(file, n, key, e.what());
  }
  return v;
}

}  // namespace

ServerSettings parse_server_settings(const CellConfig& cfg) {
  ServerSettings out;
  if (cfg.document.IsNull() || !cfg.document.IsMap()) return out;
  const YAML::Node s = cfg.document["servers"];
  if (!s) return out;
  const std::string& f = cfg.file;
  only(f, s, "servers", {"fatek", "modbus"});
  if (const auto n = s["fatek"]) {
    only(f, n, "servers.fatek", {"tcp", "serial", "station", "writable", "max_connections", "idle_timeout"});
    auto& o = out.fatek;
    if (n["tcp"]) o.tcp = host_port(f, n["tcp"], "servers.fatek.tcp");
    if (n["serial"]) o.serial = serial_line(f, n["serial"], "servers.fatek.serial", "7E1");
    if (n["station"]) o.station = integer(f, n["station"], "servers.fatek.station", 1, 254);
    if (n["writable"]) o.writable = ranges(f, n["writable"], "servers.fatek.writable");
    if (n["max_connections"]) o.max_connections = integer(f, n["max_connections"], "servers.fatek.max_connections", 1, 1024);
    if (n["idle_timeout"]) o.idle_timeout_ms = timeout_ms(f, n["idle_timeout"], "servers.fatek.idle_timeout");
  }
  if (const auto n = s["modbus"]) {
    only(f, n, "servers.modbus", {"tcp", "rtu", "id", "writable", "max_connections", "idle_timeout"});
    auto& o = out.modbus;
    if (n["tcp"]) o.tcp = host_port(f, n["tcp"], "servers.modbus.tcp");
    if (n["rtu"]) o.rtu = serial_line(f, n["rtu"], "servers.modbus.rtu", "8E1");
    if (n["id"]) o.id = integer(f, n["id"], "servers.modbus.id", 1, 247);
    if (n["writable"]) o.writable = ranges(f, n["writable"], "servers.modbus.writable");
    if (n["max_connections"]) o.max_connections = integer(f, n["max_connections"], "servers.modbus.max_connections", 1, 1024);
    if (n["idle_timeout"]) o.idle_timeout_ms = timeout_ms(f, n["idle_timeout"], "servers.modbus.idle_timeout");
  }
  return out;
}

}  // namespace plc_cell
