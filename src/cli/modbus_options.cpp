// `plc_cell run --modbus-tcp HOST:PORT --modbus-rtu DEVICE[:BAUD[:FORMAT]] --modbus-id N`
#include <memory>
#include <vector>

#include "args.h"
#include "plc_cell/modbus/slave_servers.h"

namespace plc_cell {
namespace cli {

std::vector<std::unique_ptr<Server>> modbus_servers_from_args(Plc& plc, const Args& args) {
  modbus::SlaveOptions o;
  o.tcp = args.get("modbus-tcp");
  o.rtu = args.get("modbus-rtu");
  if (args.has("modbus-id")) {
    try {
      o.id = std::stoi(args.get("modbus-id"));
    } catch (const std::exception&) {
      throw UsageError("--modbus-id '" + args.get("modbus-id") + "' is not a number");
    }
  }
  return modbus::make_slave_servers(plc, o);
}

}  // namespace cli
}  // namespace plc_cell
