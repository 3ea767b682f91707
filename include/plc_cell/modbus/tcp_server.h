#pragma once
// Modbus/TCP slave on one Plc: one thread, a poll() loop over the listening socket
// and up to max_connections clients. A request is read only once all of its bytes
// are there (peeked MBAP length), so a stalling client never blocks the others.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "plc_cell/io/server.h"

typedef struct _modbus modbus_t;

namespace plc_cell {

class Plc;

namespace modbus {

struct TcpServerOptions {
  std::string host = "127.0.0.1";
  int port = 502;             // 0: any free port (tests); see bound_port()
  int max_connections = 16;   // further clients are accepted and closed at once
  int idle_timeout_ms = 60000;  // a connection silent this long is closed
};

class TcpServer : public Server {
 public:
  TcpServer(Plc& plc, TcpServerOptions opt);
  ~TcpServer() override;

  void start() override;
  void stop() override;
  std::string describe() const override;
  ServerStatus status() const override;
  int bound_port() const { return port_; }

 private:
  void run();

  Plc& plc_;
  TcpServerOptions opt_;
  modbus_t* ctx_ = nullptr;
  int listen_fd_ = -1;
  int wake_[2] = {-1, -1};
  int port_ = 0;
  std::thread thread_;
  mutable std::mutex mu_;
  ServerStatus st_;
};

}  // namespace modbus
}  // namespace plc_cell
