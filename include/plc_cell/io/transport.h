#pragma once
// The byte streams a protocol master talks over (the FATEK and TRi masters, the CLINK
// ports): TCP or a serial line held by its path (io/serial_line.h), with timeouts, and the
// errors a dead or silent link raises. Written once, whatever the protocol on top.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "plc_cell/core/error.h"
#include "plc_cell/io/serial_settings.h"

namespace plc_cell {

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

// A byte stream to a device. recv returns 0 on timeout; both throw CommError on a dead link.
class Transport {
 public:
  virtual ~Transport() = default;
  virtual void open() = 0;
  virtual void close() = 0;
  virtual bool is_open() const = 0;
  virtual void send(const std::string& bytes, int timeout_ms) = 0;
  virtual size_t recv(char* buf, size_t n, int timeout_ms) = 0;
  virtual std::string describe() const = 0;
  // The open stream's descriptor, for a framing library that reads and writes it itself
  // (the Modbus bridge's libmodbus context); -1 when closed or when there is none.
  virtual int fd() const { return -1; }
  // After a request got no answer, or one that could not be read: its answer, or the rest
  // of it, may still come, and a reply does not always name the request it answers (a
  // TRi reply repeats no address), so no byte of it may be taken for a later request.
  // A connection is closed (the next send opens a new one, which carries nothing of the
  // old); a serial line, which cannot be, is drained until quiet for quiet_ms (a
  // line that does not go quiet throws CommError). The device must therefore answer
  // within twice the time-out at most, or not at all.
  virtual void resynchronise(int /*quiet_ms*/) { close(); }
};
// "HOST:PORT" (HOST may be empty for 127.0.0.1).
std::unique_ptr<Transport> tcp_transport(const std::string& host_port);
std::unique_ptr<Transport> tcp_transport(const std::string& host, int port);
// The device is reopened by the next transaction after a failure (an adapter unplugged
// and plugged back is found).
std::unique_ptr<Transport> serial_transport(const SerialSettings& line);

// One request of a master, retried: attempt() sends it and waits for its answer. After a
// CommError (a timeout, a garbled answer) the link is resynchronised (resynchronise(timeout_ms):
// a late answer to it is never taken for the next request, this one's retry included) and
// the request tried up to `retries` more times; a connection that was open but turns out
// closed by the peer (its idle time-out) is opened again once without counting, since the
// request never reached it. Every retry counts in *retries_used.
template <class F>
auto with_retries(Transport& t, int retries, int timeout_ms, uint64_t* retries_used, F&& attempt)
    -> decltype(attempt()) {
  bool reconnected = false;
  for (int n = 0;; ++n) {
    const bool reused = t.is_open();
    try {
      return attempt();
    } catch (const ConnectionClosed&) {
      if (reused && !reconnected) {
        reconnected = true;
        --n;
        continue;
      }
      if (n >= retries) throw;
      ++*retries_used;
    } catch (const CommError&) {
      t.resynchronise(timeout_ms);
      if (n >= retries) throw;
      ++*retries_used;
    }
  }
}
// A TCP connection to host:port (127.0.0.1 when host is empty), made within timeout_ms: a
// host that does not answer holds its caller (and a stop() waiting for it) that long, not for
// the system's minutes. Returns a non-blocking socket with TCP_NODELAY, or -1 and *error.
int connect_tcp(const std::string& host, int port, int timeout_ms, std::string* error);
// Reads and drops what arrives on fd until nothing has come for quiet_ms, for at most
// limit_ms overall: true once quiet, false when the line kept talking (or failed).
bool drain_until_quiet(int fd, int quiet_ms, int limit_ms);
// Writes all of buf, waiting at most timeout_ms overall. Returns false on error or timeout.
bool write_all(int fd, const char* buf, size_t n, int timeout_ms);
// Waits up to timeout_ms for fd to become readable.
bool wait_readable(int fd, int timeout_ms);

}  // namespace plc_cell
