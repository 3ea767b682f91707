#pragma once
// Modbus RTU slave on a serial line (default 8E1, the FBs default). One thread.
// libmodbus opens and configures the line; frames are cut by modbus/rtu_frame.h,
// which also frames function codes we do not serve (they get exception 01).
// Frames for other slave ids and frames with a bad CRC get no answer.
#include <atomic>
#include <mutex>
#include <string>
#include <thread>

#include "plc_cell/io/serial_settings.h"
#include "plc_cell/core/writable_ranges.h"
#include "plc_cell/io/server.h"
#include "plc_cell/modbus/tri_map.h"

typedef struct _modbus modbus_t;

namespace plc_cell {

class Plc;

namespace modbus {

class RtuServer : public Server {
 public:
  RtuServer(Plc& plc, SerialSettings port, int slave_id, WritableRanges writable = {},
            MapProfile map = MapProfile::Fbs);
  // Bytes that make no frame with a good CRC are dropped this long after the last one.
  void set_frame_timeout_ms(int ms) { frame_timeout_ms_ = ms; }
  ~RtuServer() override;

  void start() override;
  void stop() override;
  std::string describe() const override;
  ServerStatus status() const override;

 private:
  void run();
  void reopen(const std::string& why);

  Plc& plc_;
  SerialSettings port_;
  int id_;
  int frame_timeout_ms_ = 50;
  WritableRanges writable_;
  MapProfile map_;
  modbus_t* ctx_ = nullptr;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  mutable std::mutex mu_;
  ServerStatus st_;
};

}  // namespace modbus
}  // namespace plc_cell
