#pragma once
// plc_node's parameters as a cell's overrides: every server setting of Cell::server_kinds()
// is a parameter ~<kind>_<key> (so a new server kind needs nothing here), and the run
// settings are ~scan_period, ~rt_priority, ~persist_file and ~persist_interval (s).
#include <ros/node_handle.h>

#include "plc_cell/runtime/cell.h"

namespace plc_cell {

// The parameters that are set, as text with their names as origins; ~program too.
// Throws plc_cell::Error for a parameter no longer read, naming its replacement.
CellOverrides cell_overrides(const ros::NodeHandle& pnh);

}  // namespace plc_cell
