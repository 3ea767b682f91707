#pragma once
// The modbus_bridge YAML: devices (TCP or RTU; several on one RTU line), poll
// groups with their own rates, typed points. docs/modbus.md has a worked example.
#include <cstdint>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/modbus/codec.h"
#include "plc_cell/modbus/slave_map.h"

namespace plc_cell {
namespace modbus {

struct Point {
  std::string name;
  Table table = Table::HoldingRegisters;
  uint32_t address = 0;  // 0-based protocol address (40001 = holding 0)
  Encoding enc;
  double scale = 1.0, offset = 0.0;  // engineering = raw * scale + offset
  bool writable() const { return table == Table::Coils || table == Table::HoldingRegisters; }
  uint32_t width() const { return table == Table::Coils || table == Table::DiscreteInputs ? 1 : register_count(enc.type); }
};

struct PollGroup {
  std::string name;
  double rate_hz = 1.0;
  double publish_period_s = 1.0;  // republish unchanged values this often
  std::vector<Point> points;
};

struct Device {
  std::string name;
  std::string tcp;  // HOST:PORT, or
  std::string rtu;  // DEVICE[:BAUD[:FORMAT]] (default 9600 8E1); devices may share a line
  int unit = 1;
  double timeout_s = 0.5;
  uint32_t max_gap = 8;  // unused registers/bits one request may read to save a request
  std::vector<PollGroup> groups;
  std::string line() const { return tcp.empty() ? "rtu:" + rtu.substr(0, rtu.find(':')) : "tcp:" + tcp; }
};

struct BridgeConfig {
  std::vector<Device> devices;
  double backoff_min_s = 0.5, backoff_max_s = 10.0;
};

// One Modbus read covering several points of one table.
struct ReadRequest {
  Table table = Table::HoldingRegisters;
  uint32_t address = 0, count = 0;
  std::vector<size_t> points;  // indices into the group's points
};

// Every key is checked; an error is a SourceError naming file:line:column and the key.
BridgeConfig parse_bridge_config(const YAML::Node& root, const std::string& file);
BridgeConfig load_bridge_config(const std::string& path);

// Coalesces a group's points into the fewest reads within the PDU limits (125
// registers, 2000 bits), bridging gaps of at most max_gap unused addresses.
std::vector<ReadRequest> plan_reads(const std::vector<Point>& points, uint32_t max_gap);

// "coil", "discrete_input", "input_register", "holding_register" (or 0x/1x/3x/4x).
Table parse_table(const std::string& s);
const char* table_name(Table t);

}  // namespace modbus
}  // namespace plc_cell
