#pragma once
// Runs the plc_cell tool (or any shell command) as a user would, capturing its output, with
// a hard time limit (test/harness/child_process.h).
#include <string>

#include "../harness/child_process.h"

namespace plc_cell {
namespace testing {

#ifdef PLC_CELL_TOOL  // the built tool's path, defined by the targets that run it
inline ToolResult run_tool(const std::string& args) { return run_shell(std::string(PLC_CELL_TOOL) + " " + args); }
#endif

}  // namespace testing
}  // namespace plc_cell
