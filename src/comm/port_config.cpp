#include "plc_cell/comm/port_config.h"

#include <climits>
#include <vector>

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/fatek/clink.h"
#include "plc_cell/modbus/fun150.h"

namespace plc_cell {
namespace {

// One port as one section declares it, with where, for the error of a second one.
struct Declared {
  int number;
  ComLine line;
  std::string key;  // "ports.1", "fatek.ports.1"
  YAML::Node at;
};

ComLine tcp_line(const std::string& host_port) {
  std::string host;
  int port = 0;
  parse_host_port(host_port, &host, &port);
  ComLine l;
  l.tcp = (host.empty() ? "127.0.0.1" : host) + ":" + std::to_string(port);
  return l;
}

void read_ports_section(const YAML::Node& section, const YamlReader& r, ErrorList* errors,
                        std::vector<Declared>* out, int* timeout_ms, bool* timeout_given) {
  if (!section.IsMap()) r.fail(section, "ports", "expected a mapping of ports 1..4 to {serial: DEVICE} or {tcp: HOST:PORT}");
  for (const auto& kv : section) {
    const std::string name = kv.first.Scalar();
    const std::string k = "ports." + name;
    errors->collect(
        [&] {
          if (name == "timeout") {
            const uint64_t us = r.duration_us(kv.second, k);
            if (us < 1000 || us > 60000000) r.fail(kv.second, k, "time-out out of range [1ms, 60s]");
            *timeout_ms = int(us / 1000);
            *timeout_given = true;
            return;
          }
          if (name.empty() || name.find_first_not_of("0123456789-+") != std::string::npos)
            r.fail(kv.first, k, "unknown key (expected a port 1..4 or timeout)");
          const int n = int(r.integer(kv.first, k, INT_MIN, INT_MAX));
          if (n < 1 || n > 4) r.fail(kv.first, k, "port " + std::to_string(n) + " outside 1..4 (COM ports 1..4)");
          if (!kv.second.IsMap()) r.fail(kv.second, k, "expected {serial: DEVICE[:BAUD[:FORMAT]]} or {tcp: HOST:PORT}");
          r.only(kv.second, k, {"serial", "tcp"});
          if (kv.second["serial"].IsDefined() == kv.second["tcp"].IsDefined())
            r.fail(kv.second, k, "give one of serial or tcp");
          Declared d{n, {}, k, kv.first};
          if (kv.second["tcp"]) {
            d.line = tcp_line(r.host_port(kv.second["tcp"], k + ".tcp"));
          } else {
            const std::string text = r.serial_line(kv.second["serial"], k + ".serial", "7E1");
            d.line.serial = parse_serial_settings(text, "7E1");
          }
          out->push_back(d);
        },
        r.file(), kv.first);
  }
}

}  // namespace

PortSettings read_port_settings(const YAML::Node& doc, const std::string& file, ErrorList* errors) {
  PortSettings s;
  const YamlReader r(file);
  std::vector<Declared> declared;
  bool timeout_given = false;
  const YAML::Node ports = doc["ports"];
  if (ports)
    errors->collect([&] { read_ports_section(ports, r, errors, &declared, &s.timeout_ms, &timeout_given); }, file, ports);
  // The older spellings, each read by its own instruction's reader.
  const YAML::Node fatek = doc["fatek"];
  int fatek_timeout_ms = s.timeout_ms;
  errors->collect(
      [&] {
        const fatek::ClinkSettings c = fatek::read_clink_settings(fatek, file);
        fatek_timeout_ms = c.timeout_ms;
        if (!fatek || !fatek["ports"]) return;
        for (const auto& kv : fatek["ports"]) {
          const int n = int(kv.first.as<int>());
          declared.push_back({n, fatek::clink_line(c.ports.at(n)), "fatek.ports." + kv.first.Scalar(), kv.first});
        }
      },
      file, fatek);
  if (fatek && fatek.IsMap() && fatek["timeout_ms"]) {
    if (timeout_given)
      errors->add(ErrorList::diagnostic(file, fatek["timeout_ms"],
                                        "key 'fatek.timeout_ms': the time-out is also given as ports.timeout "
                                        "(write it once, as ports.timeout)"));
    else
      s.timeout_ms = fatek_timeout_ms;
  }
  const YAML::Node modbus = doc["modbus"];
  errors->collect(
      [&] {
        const auto m = modbus::parse_mbus_ports(modbus, file);
        if (!modbus || !modbus["ports"]) return;
        for (const auto& kv : modbus["ports"]) {
          const int n = int(kv.first.as<int>());
          const modbus::MbusPort& p = m.at(n);
          ComLine l = p.tcp.empty() ? modbus::mbus_line(p) : tcp_line(p.tcp);
          declared.push_back({n, l, "modbus.ports." + kv.first.Scalar(), kv.first});
        }
      },
      file, modbus);
  // A port is one physical port: declared again, it must be the same line.
  std::map<int, const Declared*> first;
  for (const Declared& d : declared) {
    const auto it = first.find(d.number);
    if (it == first.end()) {
      first[d.number] = &d;
      s.lines[d.number] = d.line;
      continue;
    }
    const Declared& o = *it->second;
    if (o.line != d.line)
      errors->add(ErrorList::diagnostic(
          file, d.at,
          "key '" + d.key + "': port " + std::to_string(d.number) + " is " + d.line.to_string() + " here but " +
              o.line.to_string() + " at line " + std::to_string(YamlReader::line(o.at)) + " (" + o.key +
              "): a port is one line, used by FUN150 and FUN151 alike"));
  }
  return s;
}

PortSettings read_port_settings(const YAML::Node& doc, const std::string& file) {
  ErrorList errors;
  PortSettings s = read_port_settings(doc, file, &errors);
  errors.throw_if_any();
  return s;
}

}  // namespace plc_cell
