#pragma once
// Protocol servers that plc_node starts from its ~parameters (empty strings leave one off);
// each parameter defaults to the cell YAML's servers: section.
#include <memory>
#include <vector>

#include <ros/node_handle.h>

#include "plc_cell/config/server_settings.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/io/server.h"

namespace plc_cell {

using ServerList = std::vector<std::unique_ptr<Server>>;

// ~fatek_tcp (HOST:PORT), ~fatek_serial (DEVICE[:BAUD[:FORMAT]]), ~fatek_station.
void add_fatek_servers(Plc& plc, ros::NodeHandle& pnh, const ServerSettings& yaml, ServerList* servers);
// ~modbus_tcp, ~modbus_rtu, ~modbus_id, ~modbus_max_connections, ~modbus_idle_timeout,
// ~modbus_gateway, ~modbus_gateway_wait (s), ~modbus_gateway_retries.
void add_modbus_servers(Plc& plc, ros::NodeHandle& pnh, const ServerSettings& yaml, ServerList* servers);

}  // namespace plc_cell
