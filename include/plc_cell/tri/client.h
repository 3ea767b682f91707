#pragma once
// TRi host-link master: multi-point frames (@ ID ... FCS *) over a serial line or TCP
// (io/transport.h), with time-outs and retries. The FCS of every reply is checked; the
// PLC's command-error (ER cc) and framing-error (FE) responses become exceptions that say
// what was refused. Not thread-safe: one transaction at a time, as a TRi line is half-duplex.
#include <cstdint>
#include <memory>
#include <string>

#include "plc_cell/core/error.h"
#include "plc_cell/io/transport.h"
#include "plc_cell/tri/commands.h"

namespace plc_cell {
namespace tri {

constexpr int kDefaultBaud = 38400;  // the TRi's default line, 8N1

// The PLC answered with a command-error response: "TRi error ER03 (out of range) to RVD0FA1".
class PlcError : public Error {
 public:
  PlcError(ErrorCode c, const std::string& what) : Error(what), code(c) {}
  ErrorCode code;
};

struct ClientOptions {
  int id = 1;            // device ID of the multi-point frames, 0..255
  int timeout_ms = 1000;
  int retries = 1;       // extra attempts after a timeout or a garbled answer (never after ER)
};

class Client {
 public:
  Client(std::unique_ptr<Transport> t, ClientOptions opt = {});
  const ClientOptions& options() const { return opt_; }
  Transport& transport() { return *t_; }

  // One request and its response. Throws CommError (no answer in time, an answer that does
  // not fit the request, a bad FCS, the PLC's framing error FE) or PlcError (ER cc).
  Response transact(const Request& req);

  // Frames sent (retries included): what a poll costs on the line.
  uint64_t requests() const { return requests_; }
  uint64_t last_latency_us() const { return last_latency_us_; }

 private:
  Response once(const Request& req, const std::string& body, const std::string& bytes);
  std::unique_ptr<Transport> t_;
  ClientOptions opt_;
  uint64_t requests_ = 0;
  uint64_t last_latency_us_ = 0;
  uint64_t retries_used_ = 0;
};

}  // namespace tri
}  // namespace plc_cell
