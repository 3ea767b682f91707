#include "plc_cell/modbus/bridge_config.h"

#include <algorithm>
#include <map>
#include <set>

#include <modbus/modbus.h>

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

template <typename T>
T get(const YAML::Node& n, const char* key, T fallback, const std::string& where) {
  if (!n[key]) return fallback;
  try {
    return n[key].as<T>();
  } catch (const YAML::Exception&) {
    throw Error(where + ": '" + key + "' has the wrong type");
  }
}

// "40001"-style references: the first digit is the table, the rest is 1-based.
void parse_ref(const std::string& ref, Point* p, const std::string& where) {
  if ((ref.size() != 5 && ref.size() != 6) || ref.find_first_not_of("0123456789") != std::string::npos)
    throw Error(where + ": ref '" + ref + "' is not a 5- or 6-digit Modbus reference like \"40001\"");
  const char kind = ref[0];
  const long n = std::stol(ref.substr(1));
  if (n < 1 || n > 65536) throw Error(where + ": ref '" + ref + "' out of range");
  switch (kind) {
    case '0': p->table = Table::Coils; break;
    case '1': p->table = Table::DiscreteInputs; break;
    case '3': p->table = Table::InputRegisters; break;
    case '4': p->table = Table::HoldingRegisters; break;
    default: throw Error(where + ": ref '" + ref + "' starts with " + kind + " (expected 0, 1, 3 or 4)");
  }
  p->address = uint32_t(n - 1);
}

Point parse_point(const YAML::Node& n, const std::string& where0) {
  Point p;
  p.name = get<std::string>(n, "name", "", where0);
  const std::string where = where0 + " point '" + p.name + "'";
  if (p.name.empty()) throw Error(where0 + ": a point without 'name'");
  if (n["ref"]) {
    parse_ref(n["ref"].as<std::string>(), &p, where);
  } else {
    if (!n["address"]) throw Error(where + ": needs 'address' (0-based) and 'table', or 'ref' (\"40001\")");
    p.table = parse_table(get<std::string>(n, "table", "holding_register", where));
    const long a = get<long>(n, "address", 0, where);
    if (a < 0 || a > 65535) throw Error(where + ": address " + std::to_string(a) + " outside 0..65535");
    p.address = uint32_t(a);
  }
  const bool bits = p.table == Table::Coils || p.table == Table::DiscreteInputs;
  p.enc.type = parse_point_type(get<std::string>(n, "type", bits ? "bool" : "uint16", where));
  if (bits != (p.enc.type == PointType::Bool))
    throw Error(where + ": coils and discrete inputs are bool, registers are not");
  p.enc.byte_order = parse_order(get<std::string>(n, "byte_order", "big", where));
  p.enc.word_order = parse_order(get<std::string>(n, "word_order", "big", where));
  p.scale = get<double>(n, "scale", 1.0, where);
  p.offset = get<double>(n, "offset", 0.0, where);
  if (p.scale == 0) throw Error(where + ": scale 0");
  if (p.address + p.width() > 65536) throw Error(where + ": runs past address 65535");
  return p;
}

}  // namespace

BridgeConfig parse_bridge_config(const YAML::Node& root) {
  BridgeConfig cfg;
  cfg.backoff_min_s = get<double>(root, "backoff_min", cfg.backoff_min_s, "bridge");
  cfg.backoff_max_s = get<double>(root, "backoff_max", cfg.backoff_max_s, "bridge");
  if (!root["devices"] || !root["devices"].IsSequence()) throw Error("bridge: 'devices' must be a list");
  std::set<std::string> names;
  std::map<std::string, std::string> line_format;  // devices sharing a serial line agree on its settings
  for (const auto& dn : root["devices"]) {
    Device d;
    d.name = get<std::string>(dn, "name", "", "device");
    const std::string where = "device '" + d.name + "'";
    if (d.name.empty()) throw Error("bridge: a device without 'name'");
    d.tcp = get<std::string>(dn, "tcp", "", where);
    d.rtu = get<std::string>(dn, "rtu", "", where);
    if (d.tcp.empty() == d.rtu.empty()) throw Error(where + ": give exactly one of 'tcp' (HOST:PORT) or 'rtu' (DEVICE[:BAUD[:FORMAT]])");
    if (!d.tcp.empty()) {
      std::string h;
      int port;
      parse_host_port(d.tcp, &h, &port);
    } else {
      const std::string s = parse_serial_settings(d.rtu, "8E1").to_string();
      auto it = line_format.emplace(d.line(), s).first;
      if (it->second != s) throw Error(where + ": serial line " + d.line() + " already set up as " + it->second);
    }
    d.unit = get<int>(dn, "unit", d.unit, where);
    if (d.unit < 0 || d.unit > 255) throw Error(where + ": unit " + std::to_string(d.unit) + " outside 0..255");
    d.timeout_s = get<double>(dn, "timeout", d.timeout_s, where);
    d.max_gap = get<uint32_t>(dn, "max_gap", d.max_gap, where);
    if (!dn["groups"] || !dn["groups"].IsSequence()) throw Error(where + ": 'groups' must be a list");
    for (const auto& gn : dn["groups"]) {
      PollGroup g;
      g.name = get<std::string>(gn, "name", "", where);
      const std::string gw = where + " group '" + g.name + "'";
      g.rate_hz = get<double>(gn, "rate", g.rate_hz, gw);
      if (!(g.rate_hz > 0 && g.rate_hz <= 1000)) throw Error(gw + ": rate must be in (0, 1000] Hz");
      g.publish_period_s = get<double>(gn, "publish_period", g.publish_period_s, gw);
      if (!gn["points"] || !gn["points"].IsSequence()) throw Error(gw + ": 'points' must be a list");
      for (const auto& pn : gn["points"]) {
        g.points.push_back(parse_point(pn, gw));
        if (!names.insert(d.name + "/" + g.points.back().name).second)
          throw Error(gw + ": point '" + g.points.back().name + "' defined twice on this device");
      }
      d.groups.push_back(std::move(g));
    }
    if (!names.insert("device:" + d.name).second) throw Error(where + ": defined twice");
    cfg.devices.push_back(std::move(d));
  }
  return cfg;
}

BridgeConfig load_bridge_config(const std::string& path) {
  try {
    return parse_bridge_config(YAML::LoadFile(path));
  } catch (const YAML::Exception& e) {
    throw Error(path + ": " + e.what());
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
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
