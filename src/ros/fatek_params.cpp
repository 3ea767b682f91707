// plc_node's FATEK slave parameters.
#include <string>

#include "plc_cell/fatek/server.h"
#include "plc_cell/ros/server_params.h"

namespace plc_cell {

void add_fatek_servers(Plc& plc, ros::NodeHandle& pnh, ServerList* servers) {
  std::string tcp, serial;
  int station = 1;
  pnh.param<std::string>("fatek_tcp", tcp, "");
  pnh.param<std::string>("fatek_serial", serial, "");
  pnh.param("fatek_station", station, station);
  if (!tcp.empty()) servers->push_back(make_fatek_server(plc, "tcp", tcp, station));
  if (!serial.empty()) servers->push_back(make_fatek_server(plc, "serial", serial, station));
}

}  // namespace plc_cell
