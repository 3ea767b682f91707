#pragma once
// Subcommands of the plc_cell tool. Each returns the process exit status.
#include <string>
#include <vector>

namespace plc_cell {
namespace cli {

int cmd_sim(const std::vector<std::string>& args);
int cmd_run(const std::vector<std::string>& args);
int cmd_check(const std::vector<std::string>& args);

}  // namespace cli
}  // namespace plc_cell
