#pragma once
// Builds the Modbus slave servers that plc_node and `plc_cell run` offer.
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/writable_ranges.h"
#include "plc_cell/io/server.h"
#include "plc_cell/modbus/map_profile.h"

namespace plc_cell {

class Plc;

namespace modbus {

struct SlaveOptions {
  std::string tcp;  // HOST:PORT, "" = off
  std::string rtu;  // DEVICE[:BAUD[:FORMAT]], default 9600 8E1; "" = off
  int id = 1;       // RTU slave id (TCP answers every unit id)
  int max_connections = 16;
  int idle_timeout_ms = 60000;
  // Gateway: with a line, the TCP server answers unit `id` (and 0, 255) itself and
  // forwards other unit ids to RTU slaves on this line (needs `tcp`).
  std::string gateway;  // DEVICE[:BAUD[:FORMAT]], "" = off
  int gateway_wait_ms = 150;
  int gateway_retries = 2;
  WritableRanges writable;  // what clients may write, TCP and RTU alike (docs/security.md)
  const MapProfile* map = &fbs_map_profile();  // the map served (map_profile.h, docs/tri.md)
};

// Throws plc_cell::Error on a bad option.
std::vector<std::unique_ptr<Server>> make_slave_servers(Plc& plc, const SlaveOptions& o);

}  // namespace modbus
}  // namespace plc_cell
