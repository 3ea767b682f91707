#pragma once
// Modbus/TCP slave on one Plc: one thread, a poll() loop over the listening socket
// and up to max_connections clients. Bytes are buffered per connection and a request
// is answered once all of its bytes are there (MBAP length), so a stalling client
// never blocks the others; the time bounds are those of io/connections.h.
#include <cstdint>
#include <mutex>
#include <string>

#include "plc_cell/core/writable_ranges.h"
#include "plc_cell/io/server.h"
#include "plc_cell/modbus/map_profile.h"
#include "plc_cell/io/tcp_listener.h"

namespace plc_cell {

class Plc;

namespace modbus {

class Forwarder;

struct TcpServerOptions {
  std::string host = "127.0.0.1";
  int port = 502;             // 0: any free port (tests); see bound_port()
  int max_connections = 16;   // further clients are accepted and closed at once
  int idle_timeout_ms = 60000;  // closed this long after its last complete request
  int frame_timeout_ms = 1000;  // a request begun must be whole within this (include/plc_cell/io/connections.h)
  // Gateway: requests whose unit id is none of own_unit, 0 and 255 go to forwarder;
  // without a forwarder every unit id is answered from the PLC.
  int own_unit = 1;
  Forwarder* forwarder = nullptr;
  WritableRanges writable;  // what clients may write (default everything); else exception 02
  const MapProfile* map = &fbs_map_profile();  // the map served (map_profile.h, docs/tri.md)
};

// The transport is io/tcp_listener.h's; this class is the Modbus side of it.
class TcpServer : public Server, private TcpProtocol {
 public:
  TcpServer(Plc& plc, TcpServerOptions opt);
  ~TcpServer() override;

  void start() override;
  void stop() override;
  std::string describe() const override;
  ServerStatus status() const override;
  int bound_port() const { return listener_.port(); }

 private:
  Taken take(uint64_t conn, Session* session, std::string& in, std::string& out) override;
  void on_event(Event e, int err) override;
  void on_connections(size_t open) override;
  void count(bool ok, const std::string& err = {});

  Plc& plc_;
  TcpServerOptions opt_;
  mutable std::mutex mu_;
  ServerStatus st_;
  TcpListener listener_;  // last: its thread stops before the members it reaches go
};

}  // namespace modbus
}  // namespace plc_cell
