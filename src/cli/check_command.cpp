// plc_cell check: parse a program and list every error with file:line:column.
#include <iostream>

#include "args.h"
#include "commands.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/function_table.h"
#include "plc_cell/core/il_parser.h"
#include "plc_cell/io/protocol_functions.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {
namespace cli {

int cmd_check(const std::vector<std::string>& argv) {
  Args args(argv, {"program", "config"});
  const std::string path = args.require("program");
  try {
    // --config: the cell's generation (an FB cell has FUN72/73/85 and the FB FUN86).
    const std::string config = args.get("config");
    const CellConfig cell = config.empty() ? CellConfig() : load_cell_config(config);
    FunctionTable fns = SoftCell::functions(temp::cell_generation(cell.document, cell.file));
    const auto keep = install_protocol_functions(CellConfig(), fns);  // FUN150/151 without ports
    const Program p = load_program_file(path, fns);
    std::cout << path << ": OK, " << p.code.size() << " instructions, " << p.labels.size() << " labels\n";
    return 0;
  } catch (const SourceError& e) {
    for (const auto& d : e.diagnostics()) std::cerr << d.to_string() << "\n";
    std::cerr << e.diagnostics().size() << " error(s)\n";
    return 1;
  }
}

}  // namespace cli
}  // namespace plc_cell
