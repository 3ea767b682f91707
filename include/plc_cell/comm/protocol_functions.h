#pragma once
// FUN150 (Modbus master) and FUN151 (FATEK CPU link, free protocol) with the ports of
// the cell YAML's `modbus:` and `fatek:` sections. `plc_cell run/sim` and plc_node pass
// this to SoftCell; the core library stays free of the protocol libraries.
#include <memory>
#include <vector>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/core/function_table.h"

namespace plc_cell {

// Throws SourceError naming the config file and section on a bad port entry.
std::vector<std::shared_ptr<void>> install_protocol_functions(const CellConfig& cfg, FunctionTable& t);
// For `plc_cell check`: the same sections read with the same errors, and FUN150/151
// installed, but no port is opened and no thread started.
std::vector<std::shared_ptr<void>> check_protocol_functions(const CellConfig& cfg, FunctionTable& t);

}  // namespace plc_cell
