#pragma once
// FATEK slave servers over TCP and serial, each on one poll() thread. A client that sends
// garbage or stalls only loses its own connection; it never holds up the others. TCP
// connections are bounded in time as well as in number (include/plc_cell/io/connections.h):
// a frame must be whole within frame_timeout_ms of its first byte, idle time counts
// from the last complete request, and a full server gives the slot of a connection
// that has completed no request for frame_timeout_ms to a new client.
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/slave.h"
#include "plc_cell/io/serial_listener.h"
#include "plc_cell/io/serial_settings.h"
#include "plc_cell/io/server.h"
#include "plc_cell/io/tcp_listener.h"

namespace plc_cell {
namespace fatek {

struct TcpServerOptions {
  std::string host = "127.0.0.1";
  int port = 500;                 // FATEK Ethernet default; 0 picks a free port (tests)
  int station = 1;
  int max_connections = 8;        // as the FATEK Ethernet module
  int idle_timeout_ms = 60000;    // closed this long after its last complete request
  int frame_timeout_ms = 1000;    // a frame not whole this long after its STX closes the connection
  size_t max_pending_output = 64 * 1024;  // a client that does not read is dropped
  WritableRanges writable;        // what clients may write (default everything)
};

// The transport is io/tcp_listener.h's; this class is the FATEK side of it.
class TcpServer : public Server, private TcpProtocol {
 public:
  TcpServer(Plc& plc, TcpServerOptions opt);
  ~TcpServer() override;
  void start() override;
  void stop() override;
  std::string describe() const override;
  ServerStatus status() const override;
  int port() const { return listener_.port(); }  // the real port after start()

 private:
  std::unique_ptr<Session> open() override;
  Taken take(uint64_t conn, Session* session, std::string& in, std::string& out) override;
  void on_event(Event e, int err) override;
  void on_connections(size_t open) override { connections_ = open; }
  void note(const std::string& e);

  Plc& plc_;
  TcpServerOptions opt_;
  Slave slave_;
  std::atomic<uint64_t> connections_{0};
  std::atomic<uint64_t> framing_errors_{0};
  mutable std::mutex err_mu_;
  std::string last_error_;
  TcpListener listener_;  // last: its thread stops before the members it reaches go
};

struct SerialServerOptions {
  SerialSettings line;
  int station = 1;
  int frame_timeout_ms = 500;  // inter-byte gap that drops an unfinished frame
  WritableRanges writable;
};

class SerialServer : public Server, private SerialProtocol {
 public:
  SerialServer(Plc& plc, SerialServerOptions opt);
  ~SerialServer() override;
  void start() override;
  void stop() override;
  std::string describe() const override;
  ServerStatus status() const override;

 private:
  void feed(const uint8_t* data, size_t n, std::string& out, std::string& fault) override;
  bool in_frame() const override { return decoder_.in_frame(); }
  void drop_frame() override { decoder_.timeout(); }
  SerialServerOptions opt_;
  Slave slave_;
  Decoder decoder_;  // the listener's thread only
  std::atomic<uint64_t> framing_errors_{0};
  SerialListener listener_;  // last: its thread stops before the members it reaches go
};

// Builders for `plc_cell run` and plc_node: "HOST:PORT" and "DEVICE[:BAUD[:FORMAT]]".
// Settings shared by the command line, plc_node parameters and tests (docs/security.md).
struct ServerPolicy {
  WritableRanges writable;
  int max_connections = 8;      // TCP only
  int idle_timeout_ms = 60000;  // TCP only
};
std::unique_ptr<Server> make_tcp_server(Plc& plc, const std::string& host_port, int station,
                                        const ServerPolicy& policy = {});
std::unique_ptr<Server> make_serial_server(Plc& plc, const std::string& device_spec, int station,
                                           const ServerPolicy& policy = {});

}  // namespace fatek

}  // namespace plc_cell
