#pragma once
// Every cell extension's status (config/cell_extension.h) on /diagnostics: one entry per
// extension that reports anything, its level the worst of its statuses. A new subsystem
// reports through its extension and appears here with no change to the node.
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>

#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {

// Returns the names of the entries added (they hold references into cell: remove them by
// name before cell goes).
std::vector<std::string> add_extension_diagnostics(diagnostic_updater::Updater& updater, SoftCell& cell);

}  // namespace plc_cell
