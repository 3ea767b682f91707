#include "commands.h"

namespace plc_cell {
namespace cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> all = {sim_command(), run_command(), check_command(), test_command(), explore_command(), fatek_command(), monitor_command(), gate_command()};
  return all;
}

}  // namespace cli
}  // namespace plc_cell
