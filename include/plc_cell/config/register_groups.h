#pragma once
// Named groups of PLC registers published together as ~registers/<group>
// (plc_cell/RegisterBlock) by plc_node and fatek_bridge: one YAML form and one topic
// whether the cell is simulated or real (docs/plc-node.md "Register groups").
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/address.h"

namespace plc_cell {

struct RegisterSpan {
  Address start;
  uint32_t count = 1;
};

// How a front end names an element: parse_address unless told (tri_bridge also takes the
// TRi's names, DM[100]). Throws Error.
using AddressParser = std::function<Address(const std::string&)>;

// "R100", "R100:10" (ten elements from R100), "DR0:4", "X0:16". Throws Error.
RegisterSpan parse_register_span(const std::string& text, const AddressParser& parse = nullptr);

struct RegisterGroup {
  std::string name;   // the topic's last part: letters, digits, _
  double rate_hz = 1;
  std::vector<RegisterSpan> spans;
  std::string text;   // the points as written, comma-separated (RegisterBlock.address)
};

// A sequence of {name, rate, points}; throws SourceError naming file:line and the key.
std::vector<RegisterGroup> parse_register_groups(const YAML::Node& seq, const std::string& key,
                                                 const YamlReader& r, const AddressParser& parse = nullptr);

}  // namespace plc_cell
