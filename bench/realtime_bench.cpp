// Real-time benchmark: the conveyor demo program scanned by RealTimeLoop at a
// 1 ms period for N seconds, reporting how late the loop wakes and how long
// each scan takes.
//
//   bench_realtime [seconds] [--fifo]
//
// seconds defaults to 10. --fifo runs the loop thread SCHED_FIFO (priority 50,
// memory locked) when the system allows it; by default the loop runs as the
// product runs it, under the normal scheduler.
//
// Output is one "key value" line per figure (times in microseconds), easy to
// read and to parse.
#include <sched.h>
#include <sys/mman.h>
#include <sys/prctl.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include "plc_cell/core/plc.h"
#include "plc_cell/core/realtime_loop.h"

namespace {

// examples/conveyor/conveyor.il, inline so the benchmark does not depend on the working directory.
const char* const kConveyor = R"(
ORG     X0
OR      M1924
OR      M0
AND     X1
OUT     M0
ORG     M0
LD NOT  X3
OR      Y1
ANDLD
OUT     Y0
ORG     M0
AND     X3
AND NOT Y1
OUT     Y2
TMR     T50 15
ORG     T50
SET     Y1
ORG     Y1
AND     X4
TMR     T51 8
ORG     T51
RST     Y1
ORG TU  T51
CTR     C0 9999
ORG     M1925
FUN 8   S=RC0 D=R0
END
)";

// Nearest-rank percentile of sorted values, in microseconds.
double percentile_us(const std::vector<uint64_t>& sorted, double p) {
  if (sorted.empty()) return 0.0;
  size_t rank = static_cast<size_t>(p / 100.0 * double(sorted.size()) + 0.999999);
  rank = std::min(std::max<size_t>(rank, 1), sorted.size());
  return double(sorted[rank - 1]) / 1000.0;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 10.0;
  bool fifo = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--fifo") == 0) {
      fifo = true;
    } else {
      char* end = nullptr;
      seconds = std::strtod(argv[i], &end);
      if (end == argv[i] || *end || seconds <= 0) {
        std::fprintf(stderr, "usage: %s [seconds] [--fifo]\n", argv[0]);
        return 2;
      }
    }
  }

  plc_cell::Plc plc;
  try {
    plc.load_program_text(kConveyor, "conveyor.il");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  plc.set_input(1, true);  // the stop button is normally closed
  if (!plc.set_mode(plc_cell::RunMode::Run)) {
    std::fprintf(stderr, "error: the PLC refused RUN\n");
    return 1;
  }

  // Page faults in the loop would show up as latency; lock what we have and will get.
  if (fifo && mlockall(MCL_CURRENT | MCL_FUTURE) != 0) std::fprintf(stderr, "note: mlockall refused\n");

  plc_cell::RealTimeLoop loop(plc, std::chrono::milliseconds(1));
  loop.record_latencies(true);
  loop.set_priority(fifo ? 50 : 0);  // the loop thread also sets its timer slack to 1 ns
  // A minimal cell, so the program does real work: a part arrives every 3 s,
  // and the stopper's end switch X4 follows the stopper Y1; the part leaves
  // once the stopper is down. One lock per scan, as a ROS publisher would take.
  uint64_t scan_no = 0;
  loop.set_after_scan([&] {
    const uint64_t n = ++scan_no;
    plc.locked([n](plc_cell::ScanEngine& e, plc_cell::Memory& m) {
      const bool stopper_down = m.bit(plc_cell::Area::Y, 1);
      e.set_input(4, stopper_down);
      if (n % 3000 == 0) e.set_input(3, true);
      if (stopper_down) e.set_input(3, false);
      return 0;
    });
  });

  loop.start();
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  loop.stop();
  const std::string sched = !fifo ? "SCHED_OTHER"
                            : loop.priority_error().empty() ? "SCHED_FIFO/50"
                                                            : "SCHED_OTHER (" + loop.priority_error() + ")";

  std::vector<uint64_t> lat = loop.latencies();
  std::sort(lat.begin(), lat.end());
  const plc_cell::ScanStats stats = plc.locked([](plc_cell::ScanEngine& e, plc_cell::Memory&) { return e.stats(); });
  const auto fault = plc.locked([](plc_cell::ScanEngine& e, plc_cell::Memory&) { return e.fault(); });
  const auto parts = plc.read(plc_cell::Address{plc_cell::Area::R, plc_cell::Width::Word, 0}, 1).at(0);

  std::printf("seconds %.1f\n", seconds);
  std::printf("period_us 1000\n");
  std::printf("sched %s\n", sched.c_str());
  std::printf("timer_slack_ns 1\n");
  std::printf("scans %llu\n", static_cast<unsigned long long>(stats.scans));
  std::printf("overruns %llu\n", static_cast<unsigned long long>(stats.overruns));
  std::printf("wake_latency_p50_us %.1f\n", percentile_us(lat, 50));
  std::printf("wake_latency_p90_us %.1f\n", percentile_us(lat, 90));
  std::printf("wake_latency_p99_us %.1f\n", percentile_us(lat, 99));
  std::printf("wake_latency_p99.9_us %.1f\n", percentile_us(lat, 99.9));
  std::printf("wake_latency_max_us %.1f\n", lat.empty() ? 0.0 : double(lat.back()) / 1000.0);
  std::printf("wake_latency_avg_us %.1f\n", stats.wake_latency.avg_ns() / 1000.0);
  std::printf("cycle_avg_us %.2f\n", stats.cycle.avg_ns() / 1000.0);
  std::printf("cycle_max_us %.1f\n", double(stats.cycle.max_ns) / 1000.0);
  std::printf("parts_done %u\n", parts);  // sanity: the program really ran
  std::printf("fault %s\n", fault.empty() ? "none" : fault.c_str());
  return fault.empty() ? 0 : 1;
}
