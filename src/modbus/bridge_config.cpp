#include "plc_cell/modbus/bridge_config.h"

#include <algorithm>
#include <map>
#include <set>

#include <modbus/modbus.h>

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"
#include "plc_cell/io/serial_settings.h"

namespace plc_cell {
namespace modbus {

Table parse_table(const std::string& s) {
  if (s == "coil" || s == "coils" || s == "0x") return Table::Coils;
  if (s == "discrete_input" || s == "discrete_inputs" || s == "1x") return Table::DiscreteInputs;
  if (s == "input_register" || s == "input_registers" || s == "3x") return Table::InputRegisters;
  if (s == "holding_register" || s == "holding_registers" || s == "4x") return Table::HoldingRegisters;
  throw Error("table '" + s + "': expected coil, discrete_input, input_register or holding_register");
}

const char* table_name(Table t) {
  static const char* const n[] = {"coil", "discrete_input", "input_register", "holding_register"};
  return n[int(t)];
}

namespace {

// "40001"-style references: the first digit is the table, the rest is 1-based.
void parse_ref(const std::string& ref, Point* p) {
  if ((ref.size() != 5 && ref.size() != 6) || ref.find_first_not_of("0123456789") != std::string::npos)
    throw Error("ref '" + ref + "' is not a 5- or 6-digit Modbus reference like \"40001\"");
  const char kind = ref[0];
  const long n = std::stol(ref.substr(1));
  if (n < 1 || n > 65536) throw Error("ref '" + ref + "' out of range");
  switch (kind) {
    case '0': p->table = Table::Coils; break;
    case '1': p->table = Table::DiscreteInputs; break;
    case '3': p->table = Table::InputRegisters; break;
    case '4': p->table = Table::HoldingRegisters; break;
    default: throw Error("ref '" + ref + "' starts with " + kind + " (expected 0, 1, 3 or 4)");
  }
  p->address = uint32_t(n - 1);
}

constexpr double kAnyNumber = 1e300;

Point parse_point(const YamlReader& r, const YAML::Node& n, const std::string& key) {
  r.only(n, key, {"name", "ref", "table", "address", "type", "byte_order", "word_order", "scale", "offset"});
  Point p;
  if (!n["name"]) r.fail(n, key + ".name", "a point needs a name");
  p.name = r.topic_name(n["name"], key + ".name", "point");
  if (const YAML::Node ref = n["ref"]) {
    if (n["table"] || n["address"]) r.fail(ref, key + ".ref", "give ref (\"40001\") or table and address, not both");
    const std::string text = r.str(ref, key + ".ref");
    r.checked(ref, key + ".ref", [&] { parse_ref(text, &p); });
  } else {
    if (!n["address"]) r.fail(n, key, "needs 'address' (0-based) and 'table', or 'ref' (\"40001\")");
    if (const YAML::Node t = n["table"]) {
      const std::string text = r.str(t, key + ".table");
      p.table = r.checked(t, key + ".table", [&] { return parse_table(text); });
    }
    p.address = uint32_t(r.integer(n["address"], key + ".address", 0, 65535));
  }
  const bool bits = p.table == Table::Coils || p.table == Table::DiscreteInputs;
  if (const YAML::Node t = n["type"]) {
    const std::string text = r.str(t, key + ".type");
    p.enc.type = r.checked(t, key + ".type", [&] { return parse_point_type(text); });
    if (bits != (p.enc.type == PointType::Bool))
      r.fail(t, key + ".type", "coils and discrete inputs are bool, registers are not");
  } else {
    p.enc.type = bits ? PointType::Bool : PointType::UInt16;
  }
  for (const char* k : {"byte_order", "word_order"}) {
    if (!n[k]) continue;
    const std::string text = r.str(n[k], key + "." + k);
    (k[0] == 'b' ? p.enc.byte_order : p.enc.word_order) = r.checked(n[k], key + "." + k, [&] { return parse_order(text); });
  }
  if (n["scale"]) p.scale = r.number(n["scale"], key + ".scale", -kAnyNumber, kAnyNumber);
  if (n["offset"]) p.offset = r.number(n["offset"], key + ".offset", -kAnyNumber, kAnyNumber);
  if (p.scale == 0) r.fail(n["scale"], key + ".scale", "scale 0");
  if (p.address + p.width() > 65536) r.fail(n, key, "runs past address 65535");
  return p;
}

}  // namespace

BridgeConfig parse_bridge_config(const YAML::Node& root, const std::string& file) {
  const YamlReader r(file);
  BridgeConfig cfg;
  r.only(root, "", {"backoff_min", "backoff_max", "devices"});
  if (root["backoff_min"]) cfg.backoff_min_s = r.number(root["backoff_min"], "backoff_min", 0, 3600);
  if (root["backoff_max"]) cfg.backoff_max_s = r.number(root["backoff_max"], "backoff_max", 0, 3600);
  const YAML::Node devices = root["devices"];
  if (!devices || !devices.IsSequence()) r.fail(devices ? devices : root, "devices", "expected a list of devices");
  std::set<std::string> names;
  std::map<std::string, std::string> line_format;  // devices sharing a serial line agree on its settings
  for (size_t i = 0; i < devices.size(); ++i) {
    const YAML::Node dn = devices[i];
    const std::string dk = "devices[" + std::to_string(i) + "]";
    r.only(dn, dk, {"name", "tcp", "rtu", "unit", "timeout", "max_gap", "groups"});
    Device d;
    if (!dn["name"]) r.fail(dn, dk + ".name", "a device needs a name");
    d.name = r.topic_name(dn["name"], dk + ".name", "device");
    if (!names.insert("device:" + d.name).second) r.fail(dn["name"], dk + ".name", "device '" + d.name + "' defined twice");
    if (dn["tcp"].IsDefined() == dn["rtu"].IsDefined())
      r.fail(dn, dk, "give exactly one of 'tcp' (HOST:PORT) or 'rtu' (DEVICE[:BAUD[:FORMAT]])");
    if (dn["tcp"]) {
      d.tcp = r.host_port(dn["tcp"], dk + ".tcp");
    } else {
      d.rtu = r.serial_line(dn["rtu"], dk + ".rtu", "8E1");
      const std::string s = parse_serial_settings(d.rtu, "8E1").to_string();
      auto it = line_format.emplace(d.line(), s).first;
      if (it->second != s) r.fail(dn["rtu"], dk + ".rtu", "serial line " + d.line() + " already set up as " + it->second);
    }
    if (dn["unit"]) d.unit = r.integer(dn["unit"], dk + ".unit", 0, 255);
    if (dn["timeout"]) d.timeout_s = r.number(dn["timeout"], dk + ".timeout", 0.001, 3600);
    if (dn["max_gap"]) d.max_gap = uint32_t(r.integer(dn["max_gap"], dk + ".max_gap", 0, 65535));
    const YAML::Node groups = dn["groups"];
    if (!groups || !groups.IsSequence()) r.fail(groups ? groups : dn, dk + ".groups", "expected a list of poll groups");
    for (size_t j = 0; j < groups.size(); ++j) {
      const YAML::Node gn = groups[j];
      const std::string gk = dk + ".groups[" + std::to_string(j) + "]";
      r.only(gn, gk, {"name", "rate", "publish_period", "points"});
      PollGroup g;
      if (gn["name"]) g.name = r.str(gn["name"], gk + ".name");
      if (gn["rate"]) {
        g.rate_hz = r.number(gn["rate"], gk + ".rate", 0, 1000);
        if (g.rate_hz == 0) r.fail(gn["rate"], gk + ".rate", "rate must be in (0, 1000] Hz");
      }
      if (gn["publish_period"]) g.publish_period_s = r.number(gn["publish_period"], gk + ".publish_period", 0, 86400);
      const YAML::Node points = gn["points"];
      if (!points || !points.IsSequence()) r.fail(points ? points : gn, gk + ".points", "expected a list of points");
      for (size_t k = 0; k < points.size(); ++k) {
        const std::string pk = gk + ".points[" + std::to_string(k) + "]";
        g.points.push_back(parse_point(r, points[k], pk));
        if (!names.insert(d.name + "/" + g.points.back().name).second)
          r.fail(points[k]["name"], pk + ".name", "point '" + g.points.back().name + "' defined twice on this device");
      }
      d.groups.push_back(std::move(g));
    }
    cfg.devices.push_back(std::move(d));
  }
  return cfg;
}

BridgeConfig load_bridge_config(const std::string& path) {
  return parse_bridge_config(YamlReader::load_file(path), path);
}

std::vector<ReadRequest> plan_reads(const std::vector<Point>& points, uint32_t max_gap) {
  std::vector<ReadRequest> out;
  for (Table t : {Table::Coils, Table::DiscreteInputs, Table::InputRegisters, Table::HoldingRegisters}) {
    const uint32_t limit = (t == Table::Coils || t == Table::DiscreteInputs) ? MODBUS_MAX_READ_BITS : MODBUS_MAX_READ_REGISTERS;
    std::vector<size_t> idx;
    for (size_t i = 0; i < points.size(); ++i)
      if (points[i].table == t) idx.push_back(i);
    std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return points[a].address < points[b].address; });
    // Greedy from the lowest address: extending a read while it fits is optimal
    // for covering sorted intervals with windows of bounded length.
    for (size_t i : idx) {
      const Point& p = points[i];
      const uint32_t end = p.address + p.width();
      if (!out.empty() && out.back().table == t) {
        ReadRequest& r = out.back();
        const uint32_t r_end = r.address + r.count;
        if (p.address <= r_end + max_gap && std::max(end, r_end) - r.address <= limit) {
          r.count = std::max(end, r_end) - r.address;
          r.points.push_back(i);
          continue;
        }
      }
      ReadRequest r;
      r.table = t;
      r.address = p.address;
      r.count = p.width();
      r.points.push_back(i);
      out.push_back(std::move(r));
    }
  }
  return out;
}

}  // namespace modbus
}  // namespace plc_cell
