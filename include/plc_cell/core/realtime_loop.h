#pragma once
// Runs the scan on a steady clock at a fixed period, with wake-latency and overrun
// accounting. Missed periods are skipped, not caught up, as a PLC would.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "plc_cell/core/plc.h"

namespace plc_cell {

// Of the `missed` periods a scan ran past, those its thread's own work does not explain.
// on_cpu_ns is the CPU time the thread used from its wake-up to the end of the scan (the
// cell's scan and, on a shared thread, the scans and after-scan calls before it). That work
// alone, started on time, misses the periods it runs past the first; the others were lost
// while the thread was off the CPU (woken late, or preempted by another thread): the
// machine's overruns, not the cells'.
uint64_t overruns_off_cpu(uint64_t missed, uint64_t on_cpu_ns, uint64_t period_ns);

class RealTimeLoop {
 public:
  RealTimeLoop(Plc& plc, std::chrono::nanoseconds period);
  ~RealTimeLoop();

  // Called after every scan, outside the PLC lock (publishers, observers).
  void set_after_scan(std::function<void()> fn) { after_scan_ = std::move(fn); }
  // Keeps every wake latency (ns) for percentile reports; off by default.
  void record_latencies(bool on) { record_ = on; }
  std::vector<uint64_t> latencies() const { return latencies_; }

  // SCHED_FIFO priority 1..99 for the loop thread (0: the normal scheduler). Needs
  // CAP_SYS_NICE; if refused the loop runs normally and priority_error() says why.
  void set_priority(int p) { priority_ = p; }
  std::string priority_error() const { return priority_error_; }

  void start();
  void stop();
  bool running() const { return running_; }

 private:
  void run();

  Plc& plc_;
  std::chrono::nanoseconds period_;
  std::function<void()> after_scan_;
  std::atomic<bool> running_{false};
  std::thread thread_;
  bool record_ = false;
  int priority_ = 0;
  std::string priority_error_;
  std::vector<uint64_t> latencies_;
};

// The first deadline of a period_ns scan added at now_ns on the grid that starts at grid_ns:
// the first grid point of that period after now. PLCs of one period added at any moments
// are then due at the same instants.
uint64_t next_on_grid(uint64_t grid_ns, uint64_t now_ns, uint64_t period_ns);

// A PLC's first scan builds its state (its units' first hooks, its interrupts bound: about
// six later scans' time), so a thread given hundreds of PLCs at once would spend its first
// wake-up past the period on them. The first grid point from next on (each period_ns
// apart) at which fewer than per_wake of the first scans still to come (firsts, their
// deadlines) are due.
uint64_t first_scan_point(const std::vector<uint64_t>& firsts, uint64_t next_ns, uint64_t period_ns, size_t per_wake);

// Many PLCs scanned by one thread, each at its own period, with the same accounting as
// RealTimeLoop. Their deadlines lie on one grid (next_on_grid, from the thread's first
// PLC): PLCs of one period are due together, so cells in one process (plc_node nodelets)
// pay one wake-up per period instead of one per cell. The scans of one instant run one
// after the other, so a cell scanned after others sees their scan time as its wake latency.
class SharedScanThread {
 public:
  // The process's threads (up to kMaxThreads, each started at its first add()): the one
  // of the first `threads` with the fewest PLCs, so that cells spread over the cores.
  static constexpr unsigned kMaxThreads = 8;
  // At most this many PLCs make their first scan at one wake-up (first_scan_point): 500
  // cells added at once on two threads start over 8 ms.
  static constexpr size_t kFirstScansPerWake = 32;
  static SharedScanThread& process(unsigned threads = 1);
  ~SharedScanThread();

  // plc scanned every period from the next point of the thread's grid for that period (within one
  // period from now), continuing its engine's clock (the first scan advances it one period);
  // after_scan after each of its scans, outside the PLC lock. Returns the handle of remove().
  // priority: the cell's SCHED_FIFO priority (1..99; 0 none). The thread runs at the highest
  // priority of the PLCs it was given, as a cell's own loop would (RealTimeLoop::set_priority);
  // if refused (no CAP_SYS_NICE) it keeps its priority and priority_error() says why.
  uint64_t add(Plc& plc, std::chrono::nanoseconds period, std::function<void()> after_scan, int priority = 0);
  // Returns once the PLC is no longer scanned (not from an after_scan).
  void remove(uint64_t id);
  size_t scanned_plcs();
  int priority();
  std::string priority_error();
  // How many times the thread has woken to scan (each wake-up scans every PLC then due).
  uint64_t wakeups();

 private:
  struct Entry {
    uint64_t id;
    Plc* plc;
    uint64_t period_ns, base_us, epoch_ns, next_ns;
    std::function<void()> after_scan;
    bool scanned = false;  // its first scan has run
  };
  void run();

  std::mutex mu_;  // held while scanning: remove() waits for the scan in progress
  std::condition_variable cv_;
  std::vector<Entry> entries_;
  uint64_t next_id_ = 1;
  bool stopping_ = false;
  int priority_ = 0;
  std::string priority_error_;
  uint64_t grid_ns_ = 0;  // the deadlines' grid: the monotonic clock at the first add()
  uint64_t wakeups_ = 0;
  std::thread thread_;
};

}  // namespace plc_cell
