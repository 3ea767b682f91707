#pragma once
// A protocol server (FATEK, Modbus) serving one Plc. plc_node and `plc_cell run`
// start them from options and stop them on shutdown.
#include <cstdint>
#include <string>

namespace plc_cell {

struct ServerStatus {
  bool running = false;
  uint64_t requests = 0;     // requests answered
  uint64_t rejected = 0;     // malformed or refused requests
  uint64_t connections = 0;  // open connections now (TCP)
  std::string last_error;
  bool link_up = true;       // serial: the device is open (false while it is gone)
  uint64_t reopened = 0;     // serial: times the device came back after it was lost
};

class Server {
 public:
  virtual ~Server() = default;
  // Binds or opens its endpoint; throws plc_cell::Error naming it on failure.
  virtual void start() = 0;
  virtual void stop() = 0;
  virtual std::string describe() const = 0;  // "FATEK TCP 127.0.0.1:500 station 1"
  virtual ServerStatus status() const = 0;
};

}  // namespace plc_cell
