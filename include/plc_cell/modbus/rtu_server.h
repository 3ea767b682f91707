#pragma once
// Modbus RTU slave on a serial line (default 8E1, the FBs default). The line is the io
// layer's SerialListener (io/serial_listener.h: one thread, the device reopened by its path
// when it comes back); this class is the Modbus side of it. Frames are cut by
// modbus/rtu_frame.h, which also frames function codes we do not serve (they get exception
// 01). Frames for other slave ids and frames with a bad CRC get no answer.
#include <chrono>
#include <memory>
#include <mutex>
#include <string>

#include "plc_cell/core/writable_ranges.h"
#include "plc_cell/io/serial_listener.h"
#include "plc_cell/io/serial_settings.h"
#include "plc_cell/io/server.h"
#include "plc_cell/modbus/rtu_frame.h"
#include "plc_cell/modbus/map_profile.h"

namespace plc_cell {

class Plc;

namespace modbus {

class RtuServer : public Server, private SerialProtocol {
 public:
  RtuServer(Plc& plc, SerialSettings port, int slave_id, WritableRanges writable = {},
            const MapProfile& map = fbs_map_profile());
  // Bytes that make no frame with a good CRC are dropped this long after the last one
  // (before start()).
  void set_frame_timeout_ms(int ms) { frame_timeout_ms_ = ms; }
  ~RtuServer() override;

  void start() override;
  void stop() override;
  std::string describe() const override;
  ServerStatus status() const override;

 private:
  void feed(const uint8_t* data, size_t n, std::string& out, std::string& fault) override;
  bool in_frame() const override { return framer_.in_frame(); }
  void drop_frame() override { framer_.reset(); }
  int wake_in_ms() const override;
  void answer(const std::vector<uint8_t>& frame, std::string& out, std::string& fault);
  int64_t now_us() const;

  Plc& plc_;
  SerialSettings port_;
  int id_;
  int frame_timeout_ms_ = 50;
  WritableRanges writable_;
  const MapProfile& map_;
  const std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
  RtuFramer framer_;
  size_t garbage_seen_ = 0;
  mutable std::mutex mu_;
  uint64_t requests_ = 0, rejected_ = 0;
  std::unique_ptr<SerialListener> listener_;  // last: its thread stops before the members it reaches go
};

}  // namespace modbus
}  // namespace plc_cell
