#pragma once
// The error a `modules:` YAML gets from the temperature config parser ("no error" if none).
#include <string>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/error.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace temp {

inline std::string config_error(const std::string& yaml) {
  try {
    parse_temperature_config(YAML::Load(yaml)["modules"], "c.yaml");
  } catch (const SourceError& e) {
    return std::string(e.what());
  }
  return std::string("no error");
}

}  // namespace temp
}  // namespace plc_cell
