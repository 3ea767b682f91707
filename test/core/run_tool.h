#pragma once
// Runs the plc_cell tool (or any shell command) as a user would, capturing its output.
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace plc_cell {
namespace testing {

struct ToolResult {
  int status;       // exit status, -1 if it did not exit normally
  std::string out;  // stdout and stderr
};

inline ToolResult run_shell(const std::string& command) {
  ToolResult r{-1, ""};
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

// PLC_CELL_TOOL is the built tool's path, defined by the test target.
inline ToolResult run_tool(const std::string& args) { return run_shell(std::string(PLC_CELL_TOOL) + " " + args); }

}  // namespace testing
}  // namespace plc_cell
