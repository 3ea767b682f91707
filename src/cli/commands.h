#pragma once
// Subcommands of the plc_cell tool. Each returns the process exit status.
#include <memory>
#include <string>
#include <vector>

namespace plc_cell {
namespace cli {

int cmd_sim(const std::vector<std::string>& args);
int cmd_run(const std::vector<std::string>& args);
int cmd_check(const std::vector<std::string>& args);
// FATEK master tool (src/cli/fatek_command.cpp).
int cmd_fatek(const std::vector<std::string>& args);

}  // namespace cli
}  // namespace plc_cell
