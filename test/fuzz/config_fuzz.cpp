// Any cell YAML: the loader returns a config or throws an Error whose every message names
// the file and a line (file:line:column). An error without them, an exception of another
// kind (a yaml-cpp one escaping the reader) or a crash is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/core/error.h"
#include "plc_cell/runtime/cell.h"

namespace {

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "FINDING: %s\n", what.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    static const std::set<std::string> sections = plc_cell::Cell::sections();
    plc_cell::parse_cell_config(std::string(reinterpret_cast<const char*>(data), size), "fuzz.yaml", sections);
  } catch (const plc_cell::SourceError& e) {
    if (e.diagnostics().empty()) finding("a SourceError with no diagnostic");
    for (const auto& d : e.diagnostics())
      if (d.where.file != "fuzz.yaml" || d.where.line < 1) finding("an error that names no file:line: " + d.to_string());
  } catch (const plc_cell::Error& e) {
    finding(std::string("an error that names no file:line: ") + e.what());
  } catch (const std::exception& e) {
    finding(std::string("an exception that is not a plc_cell::Error: ") + e.what());
  }
  return 0;
}
