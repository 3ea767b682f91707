#pragma once
// A PLC of the FB generation with its `modules:` section hooked in, stepped in virtual time.
#include <memory>
#include <string>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/temp/temp_functions.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace temp {

inline FunctionTable fb_table(Generation g = Generation::FB) {
  FunctionTable t = FunctionTable::with_core_functions();
  add_temperature_functions(t, g);
  return t;
}

// A cell YAML of the FB generation with these modules.fb_temperature.modules entries
// (and whatever follows them, e.g. a plants section at two spaces).
inline std::string fb_yaml(const std::string& modules) {
  return "modules:\n  generation: FB\n  fb_temperature:\n    modules:\n" + modules;
}

struct FbCell {
  Plc p{fb_table()};
  std::unique_ptr<TemperatureCell> cell;
  uint64_t now = 0;  // us

  FbCell(const std::string& yaml, const std::string& program) {
    p.locked([&](ScanEngine& e, Memory& m) {
      cell = make_temperature_cell(YAML::Load(yaml), "fb.yaml", m);
      e.add_hook(cell.get());
      return 0;
    });
    p.load_program_text(program, "fb.il");
    p.set_mode(RunMode::Run);
  }
  ~FbCell() {
    p.locked([&](ScanEngine& e, Memory&) {
      e.remove_hook(cell.get());
      return 0;
    });
  }
  int16_t r(const char* a) { return int16_t(p.read(parse_address(a), 1)[0]); }
  void set(const char* a, uint32_t v) { p.write(parse_address(a), {v}); }
  // Scans every scan_us up to and including t_us.
  void run_to(uint64_t t_us, uint64_t scan_us = 1000) {
    for (; now <= t_us; now += scan_us) p.scan(now);
  }
};

}  // namespace temp
}  // namespace plc_cell
