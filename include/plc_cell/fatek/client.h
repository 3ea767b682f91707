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

namespace plc_cell {
namespace fatek {

// No (valid) answer: timeout, lost connection, garbled response.
class CommError : public Error {
 public:
  using Error::Error;
};
// The peer closed the connection (or the line went away).
class ConnectionClosed : public CommError {
 public:
  using CommError::CommError;
};
// The PLC answered with an error code.
class PlcError : public Error {
 public:
  PlcError(ErrorCode c, const std::string& what) : Error(what), code(c) {}
  ErrorCode code;
};

// A byte stream to the PLC. recv returns 0 on timeout; both throw CommError on a dead link.
class Transport {
 public:
  virtual ~Transport() = default;
  virtual void open() = 0;
  virtual void close() = 0;
  virtual bool is_open() const = 0;
  virtual void send(const std::string& bytes, int timeout_ms) = 0;
  virtual size_t recv(char* buf, size_t n, int timeout_ms) = 0;
  virtual std::string describe() const = 0;
};
std::unique_ptr<Transport> tcp_transport(const std::string& host_port);  // "HOST:PORT", default port 500
std::unique_ptr<Transport> serial_transport(const SerialSettings& line);

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
  bool stale_ = false;  // the last transaction failed: input may hold a late answer
};

// Items per frame of commands 44..47 for a start address of this width.
uint32_t max_block(const Address& start);

}  // namespace fatek
}  // namespace plc_cell
