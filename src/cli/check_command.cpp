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
  Args args(argv, {"program"});
  const std::string path = args.require("program");
  FunctionTable fns = SoftCell::functions();
  const auto keep = install_protocol_functions(CellConfig(), fns);  // FUN150/151 without ports
  try {
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
