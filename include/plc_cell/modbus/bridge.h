#pragma once
// The bridge's bus side (no ROS): one thread per line (a TCP connection, or a
// serial port shared by several devices), polling each group at its rate with
// the planned reads, reconnecting with exponential back-off.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "plc_cell/modbus/bridge_config.h"

typedef struct _modbus modbus_t;

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
  struct Line;
  void run(Line& line);
  bool ensure_connected(Line& line);
  void poll_group(Line& line, size_t dev, size_t group);
  void note_error(Line& line, size_t dev, int err);

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
