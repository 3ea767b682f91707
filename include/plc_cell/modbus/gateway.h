#pragma once
// Modbus/TCP -> RTU gateway with TRi FMD semantics (spec tri-fmd1616.md §4.9):
// the PLC answers its own unit id (and 0 / 255); any other unit id goes out on the
// serial line, one transaction at a time. No reply within `wait`: resend, up to
// `retries` times, then exception 0B. A request that cannot get the line (queue
// full, or queued longer than busy_ms) gets exception 06. TCP clients are served
// meanwhile: the line is an io layer ComPort (io/com_port.h: one thread, one transaction
// at a time, the device reopened by its path), and libmodbus frames on its fd.
#include <chrono>
#include <deque>
#include <memory>
#include <mutex>
#include <string>

#include "plc_cell/io/com_port.h"
#include "plc_cell/io/serial_settings.h"
#include "plc_cell/io/server.h"
#include "plc_cell/modbus/forwarder.h"
#include "plc_cell/modbus/tcp_server.h"

typedef struct _modbus modbus_t;

namespace plc_cell {

class Plc;

namespace modbus {

struct GatewayOptions {
  TcpServerOptions tcp;  // tcp.own_unit: the PLC's own id
  SerialSettings line;
  int wait_ms = 150;         // per attempt ("about 150 ms" in the TRi manual)
  int retries = 2;           // resends after the first attempt (3 attempts in all)
  size_t max_pending = 8;    // requests queued for the line, all connections together
  int busy_ms = 1000;        // queued longer than this: 06 instead of a stale transaction
};

class RtuForwarder : public Forwarder {
 public:
  explicit RtuForwarder(const GatewayOptions& o);
  ~RtuForwarder() override;
  void start();
  void stop();
  bool submit(uint64_t conn, std::vector<uint8_t> frame, Done done) override;
  uint64_t no_response() const;  // requests answered 0B

 private:
  struct Job {
    uint64_t conn;
    std::vector<uint8_t> frame;
    Done done;
    std::chrono::steady_clock::time_point queued;
  };
  void run_next();
  std::vector<uint8_t> transact(const std::vector<uint8_t>& frame);
  bool attempt(int fd, const std::vector<uint8_t>& f, std::vector<uint8_t>* reply);

  GatewayOptions opt_;
  modbus_t* ctx_ = nullptr;  // framing only, on the port's fd (libmodbus never opens or closes it)
  mutable std::mutex mu_;
  std::deque<Job> jobs_;
  bool busy_ = false, stop_ = true;
  uint64_t no_response_ = 0;
  std::unique_ptr<ComPort> port_;  // its thread runs run_next()
};

class GatewayServer : public Server {
 public:
  GatewayServer(Plc& plc, GatewayOptions o);
  ~GatewayServer() override { stop(); }  // the line before the TCP side, as stop() does
  void start() override;
  void stop() override;
  std::string describe() const override;
  ServerStatus status() const override;
  int bound_port() const { return tcp_->bound_port(); }

 private:
  GatewayOptions opt_;
  std::unique_ptr<RtuForwarder> rtu_;
  std::unique_ptr<TcpServer> tcp_;
};

}  // namespace modbus
}  // namespace plc_cell
