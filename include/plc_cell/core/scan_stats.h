#pragma once
// Scan statistics: cycle (execution) time and, in real time, wake latency and overruns.
#include <cstdint>

#include "plc_cell/core/scan_health.h"

namespace plc_cell {

struct DurationStats {
  uint64_t count = 0;
  uint64_t last_ns = 0;
  uint64_t min_ns = 0;
  uint64_t max_ns = 0;
  double sum_ns = 0;

  void add(uint64_t ns) {
    if (count == 0 || ns < min_ns) min_ns = ns;
    if (ns > max_ns) max_ns = ns;
    last_ns = ns;
    sum_ns += double(ns);
    ++count;
  }
  double avg_ns() const { return count ? sum_ns / double(count) : 0.0; }
};

struct ScanStats {
  uint64_t scans = 0;
  DurationStats cycle;         // time spent in one scan (real-time loop only)
  DurationStats wake_latency;  // how late the loop woke after its deadline
  uint64_t overruns = 0;       // periods missed because a scan ran past its deadline
  // Of those, the periods lost while the scan thread was off the CPU (woken late or
  // preempted): the machine's, not the scans' (overruns_off_cpu in realtime_loop.h).
  uint64_t overruns_off_cpu = 0;
  ScanWindow recent;           // the same, over the last seconds of scans (real-time loop only)
};

}  // namespace plc_cell
