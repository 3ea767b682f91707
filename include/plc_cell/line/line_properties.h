#pragma once
// A scenario file's properties watched over a line's run (docs/monitor.md, "Properties"):
// after each scan of a cell here, the names the properties read in that cell are read in
// one memory read (the cell's lock held for that copy only) and handed to the watcher,
// which evaluates the line's instants one after another.
#include <memory>

#include "plc_cell/line/line.h"
#include "plc_cell/scenario/property_watcher.h"

namespace plc_cell {
namespace line {

// The watcher's cells are numbered as l's. Takes l's after_scan (line.h): before the line runs.
void watch_properties(Line& l, std::shared_ptr<scenario::PropertyWatcher> watcher);

}  // namespace line
}  // namespace plc_cell
