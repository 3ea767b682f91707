#pragma once
// The bridge's bus side (no ROS): one io layer PolledLink per line (a TCP connection, or
// a serial port shared by several devices; io/polled_link.h: its thread polls each group
// at its rate with the planned reads, reconnects with exponential back-off and lets the
// writes in between two polls). libmodbus frames the requests on the line's fd.
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "plc_cell/modbus/bridge_config.h"

namespace plc_cell {
namespace modbus {

struct DeviceStatus {
  bool connected = false;
  uint64_t polls = 0, timeouts = 0, exceptions = 0, io_errors = 0, writes = 0;
  std::string last_exception;  // "02 Illegal data address", "" if none yet
  std::string last_error;
  double latency_last_ms = 0, latency_max_ms = 0, latency_sum_ms = 0;
  uint64_t latency_n = 0;
};

// One poll of one group: every point decoded, or ok = false and why.
struct GroupResult {
  size_t device = 0, group = 0;
  bool ok = false;
  std::string error;
  std::vector<Value> values;                  // per point of the group
  std::vector<double> engineering;            // raw * scale + offset
  std::vector<ReadRequest> reads;             // the blocks read
  std::vector<std::vector<uint16_t>> blocks;  // their data (bits as 0/1)
};

class Bridge {
 public:
  using Sink = std::function<void(const GroupResult&)>;
  Bridge(BridgeConfig cfg, Sink sink);
  ~Bridge();

  void start();
  void stop();
  // Writes a point by "device/point" or a unique "point"; throws plc_cell::Error.
  void write(const std::string& point, double value);
  // Drops every connection and reconnects now, back-off reset.
  void recover();
  DeviceStatus status(size_t device) const;
  const BridgeConfig& config() const { return cfg_; }

 private:
  class Line;
  bool poll_group(Line& line, size_t dev, size_t group);
  bool read_blocks(Line& line, size_t dev, GroupResult& r);
  void decode_group(size_t dev, GroupResult& r) const;
  void note_error(Line& line, size_t dev, int err);
  void link_failed(const Line& line, const std::string& why);

  BridgeConfig cfg_;
  Sink sink_;
  std::vector<std::vector<std::vector<ReadRequest>>> plans_;  // [device][group]
  std::vector<std::unique_ptr<Line>> lines_;
  std::vector<Line*> line_of_;  // per device
  mutable std::mutex status_mu_;
  std::vector<DeviceStatus> status_;
};

}  // namespace modbus
}  // namespace plc_cell
