// Any cell YAML: the loader returns a config or throws an Error naming file and line.
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/core/error.h"
#include "plc_cell/runtime/cell.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    static const std::set<std::string> sections = plc_cell::Cell::sections();
    plc_cell::parse_cell_config(std::string(reinterpret_cast<const char*>(data), size), "fuzz.yaml", sections);
  } catch (const plc_cell::Error&) {
  } catch (const YAML::Exception&) {
    // yaml-cpp's own errors past the syntax check (e.g. a bad conversion) are reported too.
  }
  return 0;
}
