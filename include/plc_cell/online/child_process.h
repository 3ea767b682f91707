#pragma once
// A command run in a process of its own with a bound on its wall time: what the gate runs
// in, so that the running cell's scan thread shares nothing with it but the CPU.
#include <cstdint>
#include <string>
#include <vector>

namespace plc_cell {
namespace online {

struct ChildResult {
  int exit_code = -1;   // -1: killed (timed out) or could not start
  bool timed_out = false;
  std::string out;      // its standard output
  std::string err;      // its standard error (the last 64 KiB)
  std::string failure;  // why it could not start ("" when it ran)
};

// Runs argv[0] (a path) with argv; past timeout_us the child is killed (SIGKILL, its pid
// only) and waited for. Standard input is /dev/null.
ChildResult run_child(const std::vector<std::string>& argv, uint64_t timeout_us);

// The plc_cell tool beside the running executable (plc_node and the tool are built and
// installed into one folder), else $PLC_CELL_TOOL, else "" (the caller says why it failed).
std::string tool_path();

}  // namespace online
}  // namespace plc_cell
