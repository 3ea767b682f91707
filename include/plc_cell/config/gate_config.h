#pragma once
// The cell YAML's `gate:` section: the tests a change of the running program must pass
// before it is applied (docs/online-change.md, "The gate").
//
//   gate:
//     scenarios: [conveyor.scenario.yaml]   # every case and property, on the new program
//     explore: 20s                          # plus this much virtual time of plc_cell explore
//     mutate: true                          # the cases must kill the mutants of the lines changed
//     timeout: 60s                          # wall time the gate's process may take
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/config/cell_extension.h"

namespace plc_cell {

struct GateConfig {
  int line = 0;  // of `gate:`; 0: the cell has no gate
  // Paths, resolved against the cell file's folder. Read when the gate runs, not with the
  // cell: a cell copied without its tests still runs, and every change to it fails its gate.
  std::vector<std::string> scenarios;
  uint64_t explore_us = 0;             // 0: no exploration
  // Every mutant of a line the change wrote must be killed by the cases (or found
  // equivalent-suspect): the change is tested, not only not broken.
  bool mutate = false;
  uint64_t timeout_us = 60'000'000;
};

// Reads cfg's gate: section (an absent one gives line 0); throws SourceError at the key.
GateConfig read_gate(const CellConfig& cfg);

// The extension that claims `gate:` and checks it with the rest of the file; it provides
// its GateConfig as a facet. Every cell has it (SoftCell's built-ins): the gate belongs to
// the cell file, whoever reads it.
std::unique_ptr<CellExtension> gate_section();

}  // namespace plc_cell
