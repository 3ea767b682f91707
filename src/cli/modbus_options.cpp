// `plc_cell run --modbus-tcp HOST:PORT --modbus-rtu DEVICE[:BAUD[:FORMAT]] --modbus-id N
//   [--modbus-gateway DEVICE[:BAUD[:FORMAT]] --modbus-gateway-wait MS --modbus-gateway-retries N]`
#include <memory>
#include <vector>

#include "args.h"
#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/server_settings.h"
#include "plc_cell/core/writable_ranges.h"
#include "commands.h"
#include "plc_cell/modbus/slave_servers.h"

namespace plc_cell {
namespace cli {

void add_modbus_servers(const Args& args, const ServerSettings& yaml, Plc& plc,
                        std::vector<std::unique_ptr<Server>>* servers) {
  modbus::SlaveOptions o;
  const auto& y = yaml.modbus;
  o.tcp = args.has("modbus-tcp") ? args.get("modbus-tcp") : y.tcp;
  o.rtu = args.has("modbus-rtu") ? args.get("modbus-rtu") : y.rtu;
  o.id = y.id;
  o.max_connections = y.max_connections;
  o.idle_timeout_ms = y.idle_timeout_ms;
  o.writable = WritableRanges::parse(y.writable);
  o.gateway = args.get("modbus-gateway");
  if (args.has("modbus-id")) {
    try {
      o.id = std::stoi(args.get("modbus-id"));
    } catch (const std::exception&) {
      throw UsageError("--modbus-id '" + args.get("modbus-id") + "' is not a number");
    }
  }
  const auto number = [&](const char* name, int* out) {
    if (!args.has(name)) return;
    try {
      *out = std::stoi(args.get(name));
    } catch (const std::exception&) {
      throw UsageError(std::string("--") + name + " '" + args.get(name) + "' is not a number");
    }
  };
  number("modbus-gateway-wait", &o.gateway_wait_ms);
  number("modbus-max-connections", &o.max_connections);
  if (args.has("modbus-idle-timeout")) {
    const uint64_t us = parse_duration_us(args.get("modbus-idle-timeout"));
    if (us < 1000 || us > 86400000000ull) throw UsageError("--modbus-idle-timeout must be between 1ms and 24h");
    o.idle_timeout_ms = int(us / 1000);
  }
  if (args.has("modbus-writable")) o.writable = WritableRanges::parse(args.get("modbus-writable"));
  number("modbus-gateway-retries", &o.gateway_retries);
  for (auto& s : modbus::make_slave_servers(plc, o)) servers->push_back(std::move(s));
}

}  // namespace cli
}  // namespace plc_cell
