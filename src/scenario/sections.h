#pragma once
// The scenario file's sections beside its cases: properties, explore and hardware
// (docs/testing-your-cell.md). Every error into errors, at file:line with its key.
#include <vector>

#include "plc_cell/config/error_list.h"
#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace scenario {

// naming: how the file names what it reads (a line's names or a lone cell's).
std::vector<Property> read_properties(const YamlReader& r, const YAML::Node& list, ErrorList& errors, Naming naming);
ExploreSpec read_explore(const YamlReader& r, const YAML::Node& map, ErrorList& errors, Naming naming);
HardwarePermission read_hardware(const YamlReader& r, const YAML::Node& n, ErrorList& errors);

}  // namespace scenario
}  // namespace plc_cell
