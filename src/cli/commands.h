#pragma once
// Subcommands of the plc_cell tool. Each returns the process exit status.
#include <memory>
#include <string>
#include <vector>

namespace plc_cell {
class Plc;
class Server;
struct ServerSettings;
namespace cli {
class Args;

int cmd_sim(const std::vector<std::string>& args);
int cmd_run(const std::vector<std::string>& args);
int cmd_check(const std::vector<std::string>& args);
// FATEK master tool (src/cli/fatek_command.cpp).
int cmd_fatek(const std::vector<std::string>& args);
// Servers of `plc_cell run --fatek-tcp/--fatek-serial [--station N]`.
// Defaults from the cell YAML's servers: section, each field overridden by its option.
void add_fatek_servers(const Args& args, const ServerSettings& yaml, Plc& plc, std::vector<std::unique_ptr<Server>>* servers);
// Servers of `plc_cell run --modbus-tcp/--modbus-rtu/--modbus-gateway ...` (modbus_options.cpp).
void add_modbus_servers(const Args& args, const ServerSettings& yaml, Plc& plc, std::vector<std::unique_ptr<Server>>* servers);

}  // namespace cli
}  // namespace plc_cell
