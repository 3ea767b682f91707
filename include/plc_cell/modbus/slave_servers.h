#pragma once
// Builds the Modbus slave servers that plc_node and `plc_cell run` offer.
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/io/server.h"

namespace plc_cell {

class Plc;

namespace modbus {

struct SlaveOptions {
  std::string tcp;  // HOST:PORT, "" = off
  std::string rtu;  // DEVICE[:BAUD[:FORMAT]], default 9600 8E1; "" = off
  int id = 1;       // RTU slave id (TCP answers every unit id)
  int max_connections = 16;
  int idle_timeout_ms = 60000;
};

// Throws plc_cell::Error on a bad option.
std::vector<std::unique_ptr<Server>> make_slave_servers(Plc& plc, const SlaveOptions& o);

}  // namespace modbus
}  // namespace plc_cell
