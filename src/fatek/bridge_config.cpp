#include "plc_cell/fatek/bridge_config.h"

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"

namespace plc_cell {
namespace fatek {

void check_link_settings(const BridgeConfig& cfg) {
  if (cfg.tcp.empty() == cfg.serial.empty()) throw Error("give exactly one of tcp (HOST:PORT) or serial (DEVICE[:BAUD[:FORMAT]])");
  if (cfg.station < 1 || cfg.station > 254) throw Error("station " + std::to_string(cfg.station) + " outside 1..254");
  if (!(cfg.timeout_s > 0)) throw Error("timeout must be positive");
  if (cfg.retries < 0) throw Error("retries must not be negative");
  if (!(cfg.io_rate_hz > 0 && cfg.io_rate_hz <= 100)) throw Error("I/O rate must be in (0, 100] Hz");
  if (!(cfg.backoff_min_s > 0 && cfg.backoff_min_s <= cfg.backoff_max_s))
    throw Error("back-off must be 0 < min <= max");
}

BridgeConfig parse_bridge_config(const YAML::Node& root, const std::string& file) {
  const YamlReader r(file);
  // The bridge's part of a larger file sits under `fatek_bridge:`, and then is all of it.
  YAML::Node doc = root;
  std::string prefix;
  if (root.IsMap() && root["fatek_bridge"]) {
    r.only(root, "", {"fatek_bridge"});
    doc = root["fatek_bridge"];
    prefix = "fatek_bridge.";
  }
  r.only(doc, prefix.empty() ? "" : "fatek_bridge", {"signals", "groups"});
  BridgeConfig cfg;
  if (const YAML::Node sig = doc["signals"]) cfg.signals = r.discretes(sig, prefix + "signals");
  if (const YAML::Node groups = doc["groups"]) cfg.groups = parse_register_groups(groups, prefix + "groups", r);
  return cfg;
}

BridgeConfig load_bridge_config(const std::string& path) {
  return parse_bridge_config(YamlReader::load_file(path), path);
}

}  // namespace fatek
}  // namespace plc_cell
