#pragma once
// The monitor's HTTP and WebSocket server (docs/monitor-api.md): the page, its API and its
// live frames, served from a monitor::Source it does not look behind (the cell in this
// process, a real PLC, a recording). Read-only unless writable ranges are given; every
// request's Host and Origin are checked, and a write needs the session's token.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/config/server_kind.h"
#include "plc_cell/core/writable_ranges.h"
#include "plc_cell/io/server.h"
#include "plc_cell/monitor/source.h"
#include "plc_cell/monitor/source_set.h"

namespace plc_cell {
namespace monitor {

struct HttpSettings {
  std::string endpoint = "127.0.0.1:8080";  // HOST:PORT; port 0 picks a free one
  WritableRanges writable = WritableRanges::parse("none");
  int max_connections = 16;
  uint64_t idle_timeout_us = 60'000'000;
  // A request's headers must be whole this long after its first byte, or the connection is
  // closed (a client that sends half a request and waits holds no slot for long).
  uint64_t header_timeout_us = 2'000'000;
  std::vector<std::string> allowed_hosts;  // Host names accepted besides loopback and the bound address
  std::string asset_root;                  // the page's files ("" = default_asset_root())
  std::string vendor_root = "/usr/share/javascript";  // /vendor/<lib>/... (Debian's libjs-*)
  // Pages may change the running program (Apply, Undo: docs/online-change.md); only with
  // writable all, and every change with the session's token.
  bool edit = false;
};

// The page's folder: $PLC_CELL_MONITOR_ASSETS, else share/monitor of the source tree this
// was built from, else of the installed package.
std::string default_asset_root();

// The `http` server kind's settings (servers.http.*, --http-*, ~http_*) after the merge.
HttpSettings http_settings(const Settings& settings);

class HttpServer : public Server {
 public:
  HttpServer(Source& source, HttpSettings settings);
  // Owns its source (the `http` server kind of a cell owns the cell's LiveSource).
  HttpServer(std::unique_ptr<Source> source, HttpSettings settings);
  // Several cells (a line's): an overview at /, each cell's page at /cell/NAME/
  // (docs/monitor-api.md, "A line's cells"). Throws Error for an empty set.
  HttpServer(SourceSet cells, HttpSettings settings);
  ~HttpServer() override;

  // Binds; throws plc_cell::Error naming the endpoint. After a stop() it serves again, on
  // the port the first start bound (the one picked for port 0) and with the same token.
  void start() override;
  void stop() override;  // closes every connection; start() may follow
  std::string describe() const override;  // "monitor http://127.0.0.1:8080/"
  ServerStatus status() const override;

  uint16_t port() const;  // the bound port (after start)
  const std::string& token() const;  // what a write's X-Plc-Token must be

 private:
  class Impl;
  std::unique_ptr<Source> owned_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace monitor
}  // namespace plc_cell
