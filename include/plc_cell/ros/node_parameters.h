#pragma once
// The private parameters plc_node reads, as one schema: a name set under the node's
// namespace that is not in it (a misspelling such as ~io_rte) would otherwise be ignored
// without a word, and the node would run on the default.
#include <string>
#include <vector>

#include <ros/node_handle.h>

namespace plc_cell {

// Every private parameter plc_node reads: its own, the run settings and each server
// kind's (so a new server kind or run setting is known without an edit here).
std::vector<std::string> plc_node_parameters();

// The names set under pnh's namespace (first level, "~name") that are not in known,
// sorted.
std::vector<std::string> unknown_parameters(const ros::NodeHandle& pnh, const std::vector<std::string>& known);

}  // namespace plc_cell
