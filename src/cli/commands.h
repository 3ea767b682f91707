#pragma once
// The subcommands of the plc_cell tool. Each command's file defines its Command (name,
// usage lines, entry point); commands.cpp lists them, and main.cpp dispatches and prints
// --help from that list alone.
#include <string>
#include <vector>

namespace plc_cell {
namespace cli {

struct Command {
  const char* name;
  const char* usage;  // its lines of --help, set in the usage column (their leading blanks dropped)
  int (*run)(const std::vector<std::string>& args);  // the process exit status
};

Command sim_command();
Command run_command();
Command check_command();
Command fatek_command();
Command test_command();     // scenario files (src/cli/test_command.cpp)
Command explore_command();  // random runs against properties (src/cli/explore_command.cpp)
Command monitor_command();
Command gate_command();     // the tests a change in RUN must pass (src/cli/gate_command.cpp)  // the browser monitor on a recording or a real PLC (src/cli/monitor_command.cpp)

// Every subcommand, in the order --help lists them.
const std::vector<Command>& commands();

}  // namespace cli
}  // namespace plc_cell
