#pragma once
// The TRi bridge's settings: where the PLC is and how the link is timed (given by the
// front end, e.g. tri_bridge's ~parameters), and what is polled besides the I/O image
// (the YAML's io, signals and register groups). docs/tri.md, "tri_bridge".
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/config/register_groups.h"
#include "plc_cell/core/address.h"

namespace plc_cell {
namespace tri {

struct BridgeConfig {
  std::string tcp;     // HOST:PORT (the FServer port is 9080), or
  std::string serial;  // DEVICE[:BAUD[:FORMAT]] (default 38400 8N1)
  int id = 1;          // device ID of the multi-point frames, 0..255
  double timeout_s = 0.5;
  int retries = 1;     // after a timeout or a garbled answer
  double io_rate_hz = 10;
  double backoff_min_s = 0.1, backoff_max_s = 10.0;
  uint32_t inputs = 16, outputs = 16;  // points of ~io polled (multiples of 16, 16 to 256): the FMD1616's 16 and 16
  std::vector<std::pair<std::string, Address>> signals;  // polled with the I/O image
  std::vector<RegisterGroup> groups;                      // each at its own rate
};

// Throws Error naming the first setting out of its bounds.
void check_link_settings(const BridgeConfig& cfg);

// The YAML's `io:`, `signals:` and `groups:` (optionally under a top-level `tri_bridge:`);
// points are plc_node addresses or TRi names (tri/poll_plan.h, parse_point). Every key is
// checked; an error is a SourceError naming file:line:column and the key.
BridgeConfig parse_bridge_config(const YAML::Node& root, const std::string& file);
BridgeConfig load_bridge_config(const std::string& path);

}  // namespace tri
}  // namespace plc_cell
