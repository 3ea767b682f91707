#pragma once
// SIGINT/SIGTERM as an event that one thread reads, instead of a handler that runs at a
// random moment in a random thread. The constructor blocks both signals in the calling
// thread and opens a signalfd for them; threads started afterwards inherit the mask, so
// the kernel keeps a signal pending until the owner reads it. Nothing runs in signal
// context (no async-signal-safety to get wrong, no flag shared between threads), and a
// signal sent during start-up is not lost and does not kill the process: it is seen by
// the first wait_for() once the servers and the store are up, and the stop is clean.
//
// Construct it first thing in main (or in the command), before any thread exists: a
// thread started earlier keeps both signals unblocked and would take the default action.
#include <chrono>
#include <cstdint>

namespace plc_cell {

class StopSignal {
 public:
  StopSignal();   // throws plc_cell::Error if the signalfd cannot be made
  ~StopSignal();  // closes the signalfd; the signals stay blocked (the process is ending)
  StopSignal(const StopSignal&) = delete;
  StopSignal& operator=(const StopSignal&) = delete;

  // Waits up to `timeout` for SIGINT or SIGTERM. True once one has arrived (and from then
  // on, at once); false on timeout. Call from one thread only.
  bool wait_for(std::chrono::milliseconds timeout);
  // Waits for SIGINT or SIGTERM, or, when duration_us > 0, until duration_us after the call:
  // the foreground commands' "until interrupted, or for --duration". True on a signal.
  bool wait_until_stopped(uint64_t duration_us);
  // The signal that asked for the stop (SIGINT or SIGTERM), 0 while none has.
  int signal_number() const { return signo_; }
  // "SIGTERM", "SIGINT" or "" for log lines.
  const char* signal_name() const;

 private:
  int fd_ = -1;
  int signo_ = 0;
};

}  // namespace plc_cell
