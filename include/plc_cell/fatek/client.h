#pragma once
// FATEK master: the codec over a serial line or TCP, with timeouts, retries, and reads and
// writes split into the largest legal frames. Not thread-safe (one transaction at a time,
// as a FATEK line is half-duplex).
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/error.h"
#include "plc_cell/fatek/protocol.h"
#include "plc_cell/io/serial_settings.h"
#include "plc_cell/io/transport.h"

namespace plc_cell {
namespace fatek {

// The link (io/transport.h): the errors of a dead or silent link and the byte streams.
using plc_cell::CommError;
using plc_cell::ConnectionClosed;
using plc_cell::serial_transport;
using plc_cell::tcp_transport;  // "HOST:PORT"; a FATEK PLC listens on 500
using plc_cell::Transport;

// The PLC answered with an error code.
class PlcError : public Error {
 public:
  PlcError(ErrorCode c, const std::string& what) : Error(what), code(c) {}
  ErrorCode code;
};

struct ClientOptions {
  int station = 1;      // 0 = broadcast: writes only, no answer awaited
  int timeout_ms = 1000;
  int retries = 2;      // extra attempts after a timeout or garbled answer (never after a PLC error)
};

struct PlcStatus {
  bool run = false;
  uint8_t status1 = 0;
  std::vector<uint8_t> bytes;  // all status bytes as received
};

class Client {
 public:
  Client(std::unique_ptr<Transport> t, ClientOptions opt = {});
  const ClientOptions& options() const { return opt_; }
  void set_station(int s) { opt_.station = s; }
  Transport& transport() { return *t_; }

  // One request/response (retried on timeouts). Throws CommError, or PlcError on an error code.
  Response transact(Request req);

  PlcStatus status();           // 40
  PlcStatus detailed_status();  // 53
  void set_run(bool run);       // 41
  void control(const Address& point, Action a);  // 42
  // 43: true = DISABLE (plc_cell polarity, docs/fatek.md).
  std::vector<bool> read_disabled(const Address& start, uint32_t count);
  // 44/46 and 45/47, split into frames of at most 256 discretes, 64 words or 32 DWs.
  std::vector<uint32_t> read(const Address& start, uint32_t count);
  void write(const Address& start, const std::vector<uint32_t>& values);
  // 48/49, split by weight (64 / 32).
  std::vector<uint32_t> read_mixed(const std::vector<Address>& points);
  void write_mixed(const std::vector<Address>& points, const std::vector<uint32_t>& values);
  std::string loopback(const std::string& text);  // 4E

  uint64_t last_latency_us() const { return last_latency_us_; }
  uint64_t retries_used() const { return retries_used_; }

 private:
  Response once(const Request& req, const std::string& bytes);
  std::unique_ptr<Transport> t_;
  ClientOptions opt_;
  Decoder dec_;
  uint64_t last_latency_us_ = 0;
  uint64_t retries_used_ = 0;
};

// Items per frame of commands 44..47 for a start address of this width.
uint32_t max_block(const Address& start);

}  // namespace fatek
}  // namespace plc_cell
