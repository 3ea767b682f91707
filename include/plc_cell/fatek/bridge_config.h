#pragma once
// The FATEK bridge's settings: where the PLC is and how the link is timed (given by the
// front end, e.g. fatek_bridge's ~parameters), and what is polled besides the I/O image
// (the YAML's named signals and register groups). docs/fatek.md, "fatek_bridge".
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/config/register_groups.h"
#include "plc_cell/core/address.h"

namespace plc_cell {
namespace fatek {

struct BridgeConfig {
  std::string tcp;     // HOST:PORT (default port 500), or
  std::string serial;  // DEVICE[:BAUD[:FORMAT]] (default 9600 7E1)
  int station = 1;     // 1..254: a bridge polls, so it never broadcasts
  double timeout_s = 0.5;
  int retries = 1;     // after a timeout or a garbled answer (ClientOptions::retries)
  double io_rate_hz = 10;
  double backoff_min_s = 0.1, backoff_max_s = 10.0;
  std::vector<std::pair<std::string, Address>> signals;  // polled with the I/O image
  std::vector<RegisterGroup> groups;                      // each at its own rate
};

// Throws Error naming the first setting out of its bounds.
void check_link_settings(const BridgeConfig& cfg);

// The YAML's `signals:` and `groups:` (optionally under a top-level `fatek_bridge:`); the
// link settings keep their defaults. Every key is checked; an error is a SourceError
// naming file:line:column and the key.
BridgeConfig parse_bridge_config(const YAML::Node& root, const std::string& file);
BridgeConfig load_bridge_config(const std::string& path);

}  // namespace fatek
}  // namespace plc_cell
