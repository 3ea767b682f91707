#pragma once
// Runs the scan on a steady clock at a fixed period, with wake-latency and overrun
// accounting. Missed periods are skipped, not caught up, as a PLC would.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "plc_cell/core/plc.h"

namespace plc_cell {

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

}  // namespace plc_cell
