// plc_cell check: build the cell as sim, run and plc_node do, stop, and list every error
// with file:line:column.
#include <iostream>

#include "args.h"
#include "commands.h"
#include "plc_cell/core/error.h"
#include "cell_options.h"
#include "plc_cell/runtime/cell.h"

namespace plc_cell {
namespace cli {

int cmd_check(const std::vector<std::string>& argv) {
  Args args(argv, {"program", "config"});
  if (!args.positional().empty()) throw UsageError("unexpected argument '" + args.positional()[0] + "'");
  if (!args.has("config")) args.require("program");
  try {
    // The same Cell as sim/run/plc_node; only FUN150/151 get no ports (nothing is opened).
    Cell cell(args.get("config"), cell_overrides(args), Cell::Purpose::Check);
    const auto size = cell.plc().locked([](ScanEngine& e, Memory&) {
      return std::make_pair(e.program().code.size(), e.program().labels.size());
    });
    // Operands the PLC accepts but refuses at run time: warned, the check still passes.
    const auto warnings = cell.soft().warnings();
    for (const auto& w : warnings) std::cerr << w.to_string() << "\n";
    if (!warnings.empty()) std::cerr << warnings.size() << " warning(s)\n";
    if (!cell.config().file.empty()) std::cout << cell.config().file << ": OK, cell " << cell.config().name << "\n";
    std::cout << cell.program_path() << ": OK, " << size.first << " instructions, " << size.second << " labels\n";
    return 0;
  } catch (const SourceError& e) {
    for (const auto& d : e.diagnostics()) std::cerr << d.to_string() << "\n";
    std::cerr << e.diagnostics().size() << " error(s)\n";
    return 1;
  }
}

Command check_command() {
  return {"check",
          "--program FILE [--config CELL.yaml]   build the cell, stop, and report every error and warning\n",
          cmd_check};
}

}  // namespace cli
}  // namespace plc_cell
