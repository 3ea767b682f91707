#pragma once
// The Modbus slave (TCP, RTU, TCP-to-RTU gateway) as a server kind: servers.modbus in the
// cell YAML, ~modbus_* on plc_node, --modbus-* on `plc_cell run` (docs/modbus.md).
#include "plc_cell/config/server_kind.h"

namespace plc_cell {
namespace modbus {

ServerKind server_kind();

}  // namespace modbus
}  // namespace plc_cell
