#include "plc_cell/tri/bridge_config.h"

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"
#include "plc_cell/tri/poll_plan.h"

namespace plc_cell {
namespace tri {

void check_link_settings(const BridgeConfig& cfg) {
  if (cfg.tcp.empty() == cfg.serial.empty()) throw Error("give exactly one of tcp (HOST:PORT) or serial (DEVICE[:BAUD[:FORMAT]])");
  if (cfg.id < 0 || cfg.id > 255) throw Error("device ID " + std::to_string(cfg.id) + " outside 0..255");
  if (!(cfg.timeout_s > 0)) throw Error("timeout must be positive");
  if (cfg.retries < 0) throw Error("retries must not be negative");
  if (!(cfg.io_rate_hz > 0 && cfg.io_rate_hz <= 100)) throw Error("I/O rate must be in (0, 100] Hz");
  if (!(cfg.backoff_min_s > 0 && cfg.backoff_min_s <= cfg.backoff_max_s))
    throw Error("back-off must be 0 < min <= max");
  if (cfg.inputs % 16 || cfg.inputs < 16 || cfg.inputs > 256 || cfg.outputs % 16 || cfg.outputs < 16 ||
      cfg.outputs > 256)
    throw Error("io inputs and outputs must be multiples of 16 from 16 to 256");
}

BridgeConfig parse_bridge_config(const YAML::Node& root, const std::string& file) {
  const YamlReader r(file);
  YAML::Node doc = root;
  std::string prefix;
  if (root.IsMap() && root["tri_bridge"]) {
    r.only(root, "", {"tri_bridge"});
    doc = root["tri_bridge"];
    prefix = "tri_bridge.";
  }
  r.only(doc, prefix.empty() ? "" : "tri_bridge", {"io", "signals", "groups"});
  BridgeConfig cfg;
  if (const YAML::Node io = doc["io"]) {
    r.only(io, prefix + "io", {"inputs", "outputs"});
    for (const char* k : {"inputs", "outputs"}) {
      if (!io[k]) continue;
      const uint32_t n = uint32_t(r.integer(io[k], prefix + "io." + k, 16, 256));
      if (n % 16) r.fail(io[k], prefix + "io." + k, "a multiple of 16 (the TRi reads them 16 a frame)");
      (std::string(k) == "inputs" ? cfg.inputs : cfg.outputs) = n;
    }
  }
  if (const YAML::Node sig = doc["signals"]) {
    cfg.signals = r.discretes(sig, prefix + "signals");
    for (const auto& kv : sig) {
      try {
        check_on_tri(parse_address(kv.second.as<std::string>()), 1);
      } catch (const Error& e) {
        r.fail(kv.second, prefix + "signals." + kv.first.as<std::string>(), e.what());
      }
    }
  }
  if (const YAML::Node groups = doc["groups"]) {
    cfg.groups = parse_register_groups(groups, prefix + "groups", r, [](const std::string& t) {
      return parse_point(t);
    });
    for (const auto& g : cfg.groups)
      for (const auto& s : g.spans) {
        try {
          check_on_tri(s.start, s.count);
        } catch (const Error& e) {
          r.fail(groups, prefix + "groups." + g.name, e.what());
        }
      }
  }
  return cfg;
}

BridgeConfig load_bridge_config(const std::string& path) {
  return parse_bridge_config(YamlReader::load_file(path), path);
}

}  // namespace tri
}  // namespace plc_cell
