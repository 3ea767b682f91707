// The monitor must not disturb the scan: the real-time scan's wake latency with no page
// open and with 10 pages subscribed (10 Hz, every network of the demo conveyor and its
// signals), side by side in one run. The phases alternate (none, 10 pages, none, ...) so
// that what else the machine does falls on both alike.
//
//   bench_monitor_latency [seconds] [phases]
//
// seconds (default 20) is the whole run, split into `phases` (default 4) equal phases.
// Output: one "key value" line per figure (times in microseconds).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "../test/monitor/client.h"
#include "plc_cell/core/realtime_loop.h"
#include "plc_cell/monitor/http_server.h"
#include "plc_cell/monitor/live_source.h"
#include "plc_cell/runtime/cell.h"

using namespace plc_cell;

namespace {

constexpr int kPages = 10;

// A page: subscribes, then takes every frame until told to stop.
struct Page {
  std::thread thread;
  std::atomic<uint64_t> frames{0};
};

std::string subscription(size_t networks, const CellConfig& cfg) {
  std::string s = R"({"subscribe":{"rate_hz":10,"networks":[)";
  for (size_t n = 0; n < networks; ++n) s += (n ? "," : "") + std::to_string(n);
  s += R"(],"watch":[)";
  for (size_t i = 0; i < cfg.signals.size(); ++i) s += (i ? ",\"" : "\"") + cfg.signals[i].first + "\"";
  return s + "]}}";
}

double percentile(std::vector<uint64_t> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return double(v[std::min(v.size() - 1, size_t(p * double(v.size())))]) / 1000.0;
}

std::vector<uint64_t> run_phase(Plc& plc, std::chrono::milliseconds length) {
  RealTimeLoop loop(plc, std::chrono::milliseconds(1));
  loop.record_latencies(true);
  loop.start();
  std::this_thread::sleep_for(length);
  loop.stop();
  return loop.latencies();
}

}  // namespace

int main(int argc, char** argv) {
  const int seconds = argc > 1 ? std::atoi(argv[1]) : 20;
  const int phases = argc > 2 ? std::max(2, std::atoi(argv[2])) : 4;
  Cell cell(PLC_CELL_SOURCE_DIR "/examples/conveyor/conveyor.yaml", {}, Cell::Purpose::Simulate);
  cell.plc().set_mode(RunMode::Run);
  ServerContext context(cell.plc());
  context.config = &cell.config();
  context.extensions = &cell.soft().extensions();
  monitor::LiveSource source(context, "cell conveyor_demo");
  monitor::HttpSettings settings;
  settings.endpoint = "127.0.0.1:0";
  monitor::HttpServer server(source, settings);
  server.start();
  const auto networks = monitor_test::http_get(server.port(), "/api/ladder").json()["networks"].size();
  const std::string sub = subscription(networks, cell.config());

  std::vector<uint64_t> none, pages;
  uint64_t frames = 0;
  const auto length = std::chrono::milliseconds(seconds * 1000 / phases);
  for (int ph = 0; ph < phases; ++ph) {
    if (ph % 2 == 0) {
      auto l = run_phase(cell.plc(), length);
      none.insert(none.end(), l.begin(), l.end());
      continue;
    }
    std::atomic<bool> stop{false};
    std::vector<std::unique_ptr<Page>> open;
    for (int i = 0; i < kPages; ++i) {
      open.push_back(std::make_unique<Page>());
      Page* p = open.back().get();
      p->thread = std::thread([&, p] {
        monitor_test::WsClient ws(server.port());
        ws.send(sub);
        while (!stop && !ws.next("frame", std::chrono::milliseconds(2000)).is_null()) ++p->frames;
      });
    }
    auto l = run_phase(cell.plc(), length);
    pages.insert(pages.end(), l.begin(), l.end());
    stop = true;
    for (auto& p : open) {
      p->thread.join();
      frames += p->frames;
    }
  }
  server.stop();
  std::printf("networks %zu\n", networks);
  std::printf("scans_no_page %zu\nscans_10_pages %zu\n", none.size(), pages.size());
  std::printf("frames_received %llu\n", static_cast<unsigned long long>(frames));
  std::printf("frames_per_page_per_s %.1f\n", double(frames) / kPages / (double(seconds) * (phases / 2) / phases));
  for (auto [name, v] : {std::make_pair("no_page", &none), std::make_pair("10_pages", &pages)})
    std::printf("wake_p50_us_%s %.1f\nwake_p99_us_%s %.1f\nwake_max_us_%s %.1f\n", name, percentile(*v, 0.5), name,
                percentile(*v, 0.99), name, percentile(*v, 1.0));
  return 0;
}
