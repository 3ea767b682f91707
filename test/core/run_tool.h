#pragma once
// Runs the plc_cell tool (or any shell command) as a user would, capturing its output.
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace plc_cell {
namespace testing {

struct ToolResult {
  int status;       // exit status, -1 if it did not exit normally
  std::string out;  // stdout and stderr
};

// Runs command through sh with a hard time limit, so a hung program fails its test
// instead of hanging the suite.
inline ToolResult run_shell(const std::string& command, int limit_s = 60) {
  ToolResult r{-1, ""};
  setenv("PLC_CELL_TEST_CMD", command.c_str(), 1);  // sh reads it from the environment: no quoting
  const std::string full =
      "timeout -s KILL " + std::to_string(limit_s) + " sh -c \"$PLC_CELL_TEST_CMD\" 2>&1";
  FILE* p = popen(full.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

#ifdef PLC_CELL_TOOL  // the built tool's path, defined by the targets that run it
inline ToolResult run_tool(const std::string& args) { return run_shell(std::string(PLC_CELL_TOOL) + " " + args); }
#endif

}  // namespace testing
}  // namespace plc_cell
