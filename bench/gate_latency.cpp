// A change's gate must not disturb the running scan: the real-time scan's wake latency of
// the demo conveyor with no gate running and with gates running one after another beside
// it (each `plc_cell gate` in a process of its own, as a change from the monitor runs it),
// side by side in one run. The phases alternate (none, gates, none, ...) so that what else
// the machine does falls on both alike.
//
//   bench_gate_latency [seconds] [phases]
//
// seconds (default 20) is the whole run, split into `phases` (default 4) equal phases.
// Output: one "key value" line per figure (times in microseconds).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

#include "plc_cell/core/realtime_loop.h"
#include "plc_cell/runtime/cell.h"

using namespace plc_cell;

namespace {

double percentile(std::vector<uint64_t> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return double(v[std::min(v.size() - 1, size_t(p * double(v.size())))]) / 1000.0;
}

}  // namespace

int main(int argc, char** argv) {
  const int seconds = argc > 1 ? std::atoi(argv[1]) : 20;
  const int phases = argc > 2 ? std::max(2, std::atoi(argv[2])) : 4;
  Cell cell(PLC_CELL_SOURCE_DIR "/examples/conveyor/conveyor.yaml", {}, Cell::Purpose::Simulate);
  cell.plc().set_mode(RunMode::Run);
  std::string text = cell.changes().text();
  text.replace(text.find("CTR     C0 9999"), 15, "CTR     C0 5000");  // the part counter's preset
  std::vector<uint64_t> none, gated;
  uint64_t gates = 0, passed = 0;
  double gate_s = 0;
  const auto length = std::chrono::milliseconds(seconds * 1000 / phases);
  for (int ph = 0; ph < phases; ++ph) {
    RealTimeLoop loop(cell.plc(), std::chrono::milliseconds(1));
    loop.record_latencies(true);
    std::atomic<bool> stop{false};
    std::thread beside;
    if (ph % 2)
      beside = std::thread([&] {
        while (!stop) {
          const GateResult g = cell.changes().test(text);
          ++gates;
          passed += g.passed;
          gate_s += g.seconds;
        }
      });
    loop.start();
    std::this_thread::sleep_for(length);
    loop.stop();
    stop = true;
    if (beside.joinable()) beside.join();
    auto l = loop.latencies();
    (ph % 2 ? gated : none).insert((ph % 2 ? gated : none).end(), l.begin(), l.end());
  }
  std::printf("scans_no_gate %zu\nscans_gates %zu\ngates %llu\ngates_passed %llu\ngate_avg_s %.3f\n", none.size(),
              gated.size(), static_cast<unsigned long long>(gates), static_cast<unsigned long long>(passed),
              gates ? gate_s / double(gates) : 0.0);
  for (auto [name, v] : {std::make_pair("no_gate", &none), std::make_pair("gates", &gated)})
    std::printf("wake_p50_us_%s %.1f\nwake_p99_us_%s %.1f\nwake_max_us_%s %.1f\n", name, percentile(*v, 0.5), name,
                percentile(*v, 0.99), name, percentile(*v, 1.0));
  return 0;
}
