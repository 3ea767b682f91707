#pragma once
// One COM port of the PLC (1..4): the single owner of its line and of the one thread that
// does one transaction at a time on it. FUN150 (Modbus master) and FUN151 (FATEK link,
// free protocol) both hand their transactions to the port, so a program that uses both
// instructions on one port has one line whose transactions follow each other, never
// interleaved on the wire, as on an FBs-PLC where a port is one physical port whichever
// instruction drives it. The scan never waits: submit() queues and returns.
#include <atomic>
#include <cstdint>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "plc_cell/io/serial_line.h"
#include "plc_cell/io/serial_settings.h"

namespace plc_cell {

// Where a port's line goes: a serial device, or a TCP connection (a serial server or a
// slave on Ethernet).
struct ComLine {
  std::string tcp;        // HOST:PORT, or empty for
  SerialSettings serial;  // the serial device
  bool is_tcp() const { return !tcp.empty(); }
  std::string to_string() const;  // "tcp:10.0.0.5:502", "/dev/ttyS1:9600:7E1"
  bool operator==(const ComLine& o) const { return to_string() == o.to_string(); }
  bool operator!=(const ComLine& o) const { return !(*this == o); }
};

class ComPort {
 public:
  // Tries the line at once, so that bytes arriving before the first transaction (a
  // message for FUN151 MD2) are not lost to the flush of a later open; a line not there
  // yet is opened by the first transaction.
  ComPort(int number, ComLine line);
  // Only a line with no device: the transactions bring their own transport (tests).
  explicit ComPort(int number);
  ~ComPort();  // waits for the running transaction; queued ones are dropped
  ComPort(const ComPort&) = delete;
  ComPort& operator=(const ComPort&) = delete;

  int number() const { return number_; }
  const ComLine& line() const { return line_; }
  bool has_line() const { return has_line_; }

  // Runs job on the port's thread after every job submitted before it. Never blocks on
  // the line; the job reports back through its own state.
  void submit(std::function<void()> job);

  // For a running job only. The line's fd, opened (again, by path) if it is closed; -1
  // when it cannot be, last_error() says why.
  int fd();
  // The line is dead (I/O error, hang-up, peer closed): closed now, reopened by the
  // next fd().
  void lost(const std::string& why);
  // For a running job, after a request got no (readable) answer: no byte of that answer
  // may be taken for a later request (io/transport.h, Transport::resynchronise). A TCP
  // line is closed (the next fd() connects again); a serial line is drained until quiet
  // for quiet_ms, or closed when it does not go quiet.
  void resynchronise(int quiet_ms);
  // For a running job: whether the line is open now (nothing is tried).
  bool is_open() const { return line_.is_tcp() ? tcp_fd_ >= 0 : serial_.is_open(); }

  std::string last_error() const;
  uint64_t reopened() const;
  // Whether the line was open after the last attempt to use it (any thread: diagnostics).
  bool line_up() const { return up_.load(); }

  // The instruction instance holding the port, FUN150 and FUN151 alike (-1: free, which
  // is the port's "ready" relay M1960/M1962/M1936/M1938): one instruction uses a port at
  // a time, the others wait. Scan side only.
  int holder() const { return holder_; }
  void hold(int instance) { holder_ = instance; }
  void release() { holder_ = -1; }

 private:
  void run();
  int open_tcp();

  const int number_;
  const ComLine line_;
  const bool has_line_;
  SerialLine serial_;
  int tcp_fd_ = -1;
  bool tcp_lost_ = false;

  mutable std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::function<void()>> jobs_;
  bool stop_ = false;
  std::string error_;
  uint64_t reopened_ = 0;
  std::atomic<int> holder_{-1};
  std::atomic<bool> up_{false};
  std::thread thread_;
};

}  // namespace plc_cell
