// plc_node's Modbus slave parameters: ~modbus_tcp (HOST:PORT), ~modbus_rtu
// (DEVICE[:BAUD[:FORMAT]], default format 8E1), ~modbus_id, ~modbus_max_connections,
// ~modbus_idle_timeout (s), ~modbus_gateway (DEVICE[:BAUD[:FORMAT]]: forward other unit ids
// to RTU), ~modbus_gateway_wait (s per attempt), ~modbus_gateway_retries. Empty strings
// leave a server off.
#include <memory>
#include <sstream>
#include <vector>

#include <ros/ros.h>

#include "plc_cell/core/error.h"
#include "plc_cell/modbus/slave_servers.h"
#include "plc_cell/ros/server_params.h"

namespace plc_cell {

void add_modbus_servers(Plc& plc, ros::NodeHandle& pnh, const ServerSettings& yaml, ServerList* servers) {
  modbus::SlaveOptions o;
  o.id = yaml.modbus.id;
  o.max_connections = yaml.modbus.max_connections;
  o.idle_timeout_ms = yaml.modbus.idle_timeout_ms;
  double idle = o.idle_timeout_ms / 1000.0;
  pnh.param<std::string>("modbus_tcp", o.tcp, yaml.modbus.tcp);
  pnh.param<std::string>("modbus_rtu", o.rtu, yaml.modbus.rtu);
  pnh.param("modbus_id", o.id, o.id);
  pnh.param("modbus_max_connections", o.max_connections, o.max_connections);
  pnh.param("modbus_idle_timeout", idle, idle);
  pnh.param<std::string>("modbus_gateway", o.gateway, "");
  // Silently ignoring the old name would run the gateway at the default instead.
  if (pnh.hasParam("modbus_gateway_wait_ms"))
    throw Error("~modbus_gateway_wait_ms is no longer read: give ~modbus_gateway_wait in seconds");
  double wait = o.gateway_wait_ms / 1000.0;
  pnh.param("modbus_gateway_wait", wait, wait);
  // Refused here, with the parameter's name and unit, rather than as the gateway's
  // generic "out of range" after rounding to milliseconds.
  if (!(wait >= 0.001 && wait <= 60)) {
    std::ostringstream m;
    m << "~modbus_gateway_wait " << wait << " s out of range [0.001, 60] (seconds, not ms)";
    throw Error(m.str());
  }
  o.gateway_wait_ms = int(wait * 1000 + 0.5);
  pnh.param("modbus_gateway_retries", o.gateway_retries, o.gateway_retries);
  o.idle_timeout_ms = int(idle * 1000);
  std::string writable = yaml.modbus.writable;
  pnh.param<std::string>("modbus_writable", writable, writable);
  o.writable = WritableRanges::parse(writable);
  for (auto& s : modbus::make_slave_servers(plc, o)) servers->push_back(std::move(s));
}

}  // namespace plc_cell
