// plc_node's FATEK slave parameters.
#include <string>

#include "plc_cell/fatek/server.h"
#include "plc_cell/ros/server_params.h"

namespace plc_cell {

void add_fatek_servers(Plc& plc, ros::NodeHandle& pnh, const ServerSettings& yaml, ServerList* servers) {
  std::string tcp, serial;
  int station = yaml.fatek.station;
  pnh.param<std::string>("fatek_tcp", tcp, yaml.fatek.tcp);
  pnh.param<std::string>("fatek_serial", serial, yaml.fatek.serial);
  pnh.param("fatek_station", station, station);
  fatek::ServerPolicy p;
  p.max_connections = yaml.fatek.max_connections;
  std::string writable = yaml.fatek.writable;
  double idle = yaml.fatek.idle_timeout_ms / 1000.0;
  pnh.param<std::string>("fatek_writable", writable, writable);
  pnh.param("fatek_max_connections", p.max_connections, p.max_connections);
  pnh.param("fatek_idle_timeout", idle, idle);
  p.writable = WritableRanges::parse(writable);
  p.idle_timeout_ms = int(idle * 1000);
  if (!tcp.empty()) servers->push_back(make_fatek_server(plc, "tcp", tcp, station, p));
  if (!serial.empty()) servers->push_back(make_fatek_server(plc, "serial", serial, station, p));
}

}  // namespace plc_cell
