#pragma once
// TRi host-link servers on the soft PLC: TCP (as the FMD's FServer, default port 9080)
// and serial lines (default 38400 8N1), each on one poll() thread, over the io layer's
// transports exactly as the FATEK servers (docs/architecture.md, "Transports").
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "plc_cell/core/plc.h"
#include "plc_cell/io/serial_listener.h"
#include "plc_cell/io/serial_settings.h"
#include "plc_cell/io/server.h"
#include "plc_cell/io/tcp_listener.h"
#include "plc_cell/tri/slave.h"

namespace plc_cell {
namespace tri {

constexpr int kDefaultTcpPort = 9080;  // FServer's default

struct ServerOptions {
  int id = 1;                   // device ID, 00-FF
  bool wildcard_fcs = true;     // accept the wildcard FCS "00" (AUTO mode)
  WritableRanges writable;
  int max_connections = 6;      // the FMD's 6 TCP connections
  int idle_timeout_ms = 600000; // FServer drops idle clients after 10 min
  int frame_timeout_ms = 1000;  // a frame not whole this long after its first byte: dropped
};

class TcpServer : public Server, private TcpProtocol {
 public:
  TcpServer(Plc& plc, std::string host, int port, ServerOptions opt);
  ~TcpServer() override;
  void start() override;
  void stop() override;
  std::string describe() const override;
  ServerStatus status() const override;
  int port() const { return listener_.port(); }

 private:
  std::unique_ptr<Session> open() override;
  Taken take(uint64_t conn, Session* session, std::string& in, std::string& out) override;
  void on_event(Event e, int err) override;
  void on_connections(size_t open) override { connections_ = open; }
  void note(const std::string& e);

  ServerOptions opt_;
  Slave slave_;
  std::atomic<uint64_t> connections_{0};
  mutable std::mutex err_mu_;
  std::string last_error_;
  TcpListener listener_;  // last: its thread stops before the members it reaches go
};

class SerialServer : public Server, private SerialProtocol {
 public:
  SerialServer(Plc& plc, SerialSettings line, ServerOptions opt);
  ~SerialServer() override;
  void start() override;
  void stop() override;
  std::string describe() const override;
  ServerStatus status() const override;

 private:
  void feed(const uint8_t* data, size_t n, std::string& out, std::string& fault) override;
  bool in_frame() const override { return decoder_.in_frame(); }
  void drop_frame() override { decoder_.reset(); }
  ServerOptions opt_;
  Slave slave_;
  Decoder decoder_;          // the listener's thread only
  SerialListener listener_;  // last: its thread stops before the members it reaches go
};

}  // namespace tri
}  // namespace plc_cell
