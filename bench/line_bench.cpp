// Lines of cells on one virtual clock (docs/performance.md, "Lines of cells"): chains of
// 10, 100 and 1,000 demo-like cells, each the demo conveyor's program and simulation with
// its part sensor wired from the cell before it (a travelling part), side by side with the
// same cells unwired and with the demo cell alone, so that the cost per cell and per wire as
// the line grows shows, and the memory each cell takes; and, with --real-time, the chain in
// real time on shared scan threads.
//   .build/ws/devel/lib/plc_cell/bench_line --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <malloc.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "plc_cell/core/plc.h"
#include "plc_cell/line/line.h"
#include "plc_cell/runtime/cell.h"

namespace {

using namespace plc_cell;

const std::string kDir = "/tmp/plc_cell_bench_line";
const std::string kDemoIl = std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/conveyor.il";

// The demo conveyor's cell YAML; fed: its part sensor (X3) comes from a wire, not from the
// simulation's pulse.
std::string demo_yaml(bool fed) {
  return "cell: {name: conveyor, program: " + kDemoIl +
         "}\nplc: {scan_period: 0.001}\n"
         "signals: {start_button: X0, stop_button: X1, part_present: X3, stopper_down: X4,\n"
         "          conveyor_run: Y0, stopper_lower: Y1, pick_request: Y2, line_running: M0}\n"
         "simulation:\n  inputs:\n    stop_button: {steps: [[0.0, 1]]}\n"
         "    stopper_down: {follow: {source: Y1, on_delay: 0.2, off_delay: 0.2}}\n" +
         std::string(fed ? "" : "    part_present: {pulse: {period: 5.0, width: 2.5, delay: 1.0}}\n");
}

// n cells; wired: cell i's stopper (Y1, the part let through) reaches cell i + 1's part
// sensor 2 s later and covers it 2.5 s. Unwired, every cell plays the demo's own parts.
std::string line_file(size_t n, bool wired) {
  (void)std::system(("mkdir -p " + kDir).c_str());
  std::ofstream(kDir + "/first.yaml") << demo_yaml(false);
  std::ofstream(kDir + "/fed.yaml") << demo_yaml(true);
  const std::string path = kDir + "/chain" + std::to_string(n) + (wired ? "" : "_unwired") + ".line.yaml";
  std::ofstream f(path);
  f << "cells:\n";
  for (size_t i = 0; i < n; ++i) f << "  c" << i << ": " << (wired && i > 0 ? "fed.yaml" : "first.yaml") << "\n";
  f << "wires:\n";
  if (wired)
    for (size_t i = 1; i < n; ++i)
      f << "  - {from: c" << i - 1 << ".stopper_lower, to: c" << i << ".part_present, part: {travel: 2s, length: 2.5s}}\n";
  return path;
}

// The process's resident memory now, in bytes (/proc/self/statm).
double resident_bytes() {
  std::ifstream in("/proc/self/statm");
  double pages = 0, resident = 0;
  in >> pages >> resident;
  return resident * 4096.0;
}

// The heap in use (malloc's own count: what the cells' objects take, less the machine code
// and the page tables, which only the resident size counts).
double heap_bytes() {
  const struct mallinfo2 m = mallinfo2();
  return double(m.uordblks + m.hblkhd);
}

// Instant by instant (scan_at: what a scenario's case runs, its properties checked at each
// instant), each iteration runs the line one virtual second further (1,000 instants of
// 1 ms). As plc_cell sim runs it (advance: cell by cell over windows of instants), ten.
void run_line(benchmark::State& state, bool wired, bool as_sim = false) {
  const size_t n = size_t(state.range(0));
  line::Line l(line_file(n, wired));
  l.run();
  const uint64_t seconds = as_sim ? 10 : 1;
  uint64_t t = 0;
  for (auto _ : state) {
    if (as_sim) {
      l.advance(t, t + seconds * 1000000);
      t += seconds * 1000000;
    } else {
      for (int k = 0; k < 1000; ++k, t += 1000) l.scan_at(t);
    }
  }
  const double virtual_s = double(state.iterations()) * double(seconds);
  state.counters["x_real_time"] = benchmark::Counter(virtual_s, benchmark::Counter::kIsRate);
  state.counters["ns_per_cell_scan"] = benchmark::Counter(virtual_s * 1000.0 * double(n) * 1e-9,
                                                          benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["cells"] = double(n);
  if (!l.fault().empty()) state.SkipWithError(l.fault().c_str());
}

void BM_Chain(benchmark::State& state) { run_line(state, true); }
void BM_Unwired(benchmark::State& state) { run_line(state, false); }
void BM_ChainSim(benchmark::State& state) { run_line(state, true, true); }

// The floor: the demo cell alone, scanned by Plc::scan in a loop as plc_cell sim scans it.
void BM_DemoAlone(benchmark::State& state) {
  line_file(1, false);
  Cell cell(kDir + "/first.yaml", {}, Cell::Purpose::Simulate);
  cell.plc().set_mode(RunMode::Run);
  uint64_t t = 0;
  for (auto _ : state)
    for (int k = 0; k < 1000; ++k, t += 1000) cell.plc().scan(t);
  state.counters["x_real_time"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["ns_per_cell_scan"] = benchmark::Counter(double(state.iterations()) * 1000.0 * 1e-9,
                                                          benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The same n cells with no line: each scanned by Plc::scan in turn, instant by instant. What
// the line adds per cell is BM_Unwired's time less this one's; what the cells cost more as
// they grow past the caches is this one's less BM_DemoAlone's.
void BM_Cells(benchmark::State& state) {
  const size_t n = size_t(state.range(0));
  line_file(1, false);
  std::vector<std::unique_ptr<Cell>> cells;
  for (size_t i = 0; i < n; ++i) {
    cells.push_back(std::make_unique<Cell>(kDir + "/first.yaml", CellOverrides{}, Cell::Purpose::Simulate));
    cells.back()->plc().set_mode(RunMode::Run);
  }
  uint64_t t = 0;
  for (auto _ : state)
    for (int k = 0; k < 1000; ++k, t += 1000)
      for (auto& c : cells) c->plc().scan(t);
  state.counters["x_real_time"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["ns_per_cell_scan"] =
      benchmark::Counter(double(state.iterations()) * 1000.0 * double(n) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// The dearest a wire gets: its source changes at every scan. a inverts its Y0-Y15 at every
// scan; w wires carry them to b's X16.. (scanned inputs), each change sampled, carried and
// delivered. Per wire: this one's time less the time with no wire, over w.
void BM_BusyWires(benchmark::State& state) {
  const size_t w = size_t(state.range(0));
  (void)std::system(("mkdir -p " + kDir).c_str());
  std::ofstream(kDir + "/toggle.il") << "ORG M1925\nFUN 9 MOVN S=WY0 D=WY0\nEND\n";
  std::ofstream(kDir + "/busy_a.yaml") << "cell: {name: a, program: toggle.il}\n";
  std::ofstream(kDir + "/busy_b.yaml") << "cell: {name: b, program: toggle.il}\n";
  const std::string path = kDir + "/busy" + std::to_string(w) + ".line.yaml";
  {
    std::ofstream f(path);
    f << "cells: {a: busy_a.yaml, b: busy_b.yaml}\nwires:\n";
    for (size_t i = 0; i < w; ++i) f << "  - {from: a.Y" << i << ", to: b.X" << 16 + i << "}\n";
  }
  line::Line l(path);
  l.run();
  uint64_t t = 0;
  for (auto _ : state)
    for (int k = 0; k < 1000; ++k, t += 1000) l.scan_at(t);
  state.counters["ns_per_instant"] = benchmark::Counter(double(state.iterations()) * 1000.0 * 1e-9,
                                                        benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace

BENCHMARK(BM_DemoAlone)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BusyWires)->Arg(0)->Arg(16)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Cells)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Unwired)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Chain)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ChainSim)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

// The scans' counts of every cell, summed.
struct RealTimeCounts {
  uint64_t scans = 0, overruns = 0, off_cpu = 0, cells_overrun = 0, wake_max_ns = 0;
  double wake_sum_ns = 0;
  std::vector<uint64_t> own;  // per cell: its overruns not lost off the CPU

  static RealTimeCounts of(line::Line& l) {
    RealTimeCounts c;
    for (size_t i = 0; i < l.size(); ++i) {
      const ScanStats st = l.cell(i)->plc().locked([](ScanEngine& e, Memory&) { return e.stats(); });
      c.scans += st.scans;
      c.overruns += st.overruns;
      c.off_cpu += st.overruns_off_cpu;
      c.own.push_back(st.overruns - st.overruns_off_cpu);
      c.wake_max_ns = std::max(c.wake_max_ns, st.wake_latency.max_ns);
      c.wake_sum_ns += st.wake_latency.sum_ns;
    }
    return c;
  }
  void print(const char* prefix, const RealTimeCounts& before) const {
    size_t cells = 0;
    for (size_t i = 0; i < own.size(); ++i) cells += own[i] > (before.own.empty() ? 0 : before.own[i]);
    std::printf("%sscans %llu\n%soverruns %llu\n%soverruns_off_cpu %llu\n%soverruns_from_the_cells %llu\n"
                "%scells_with_their_own_overruns %zu\n",
                prefix, static_cast<unsigned long long>(scans - before.scans), prefix,
                static_cast<unsigned long long>(overruns - before.overruns), prefix,
                static_cast<unsigned long long>(off_cpu - before.off_cpu), prefix,
                static_cast<unsigned long long>((overruns - off_cpu) - (before.overruns - before.off_cpu)), prefix,
                cells);
  }
};

// --real-time N THREADS SECONDS: the chain of N cells in real time on THREADS shared scan
// threads for SECONDS; what the cells' scans missed (the overruns, and of those the ones
// lost while a thread was off the CPU: the machine's, not the cells'), the wake latency and
// the CPU the process took, one "key value" line each: over the whole run, and again from
// the end of the first second on (steady_: every cell's first scans, which build its state
// and all come at the same instant, are behind it).
int real_time(size_t n, unsigned threads, double seconds) {
  line::Line l(line_file(n, true));
  rusage before{}, after{};
  getrusage(RUSAGE_SELF, &before);
  const auto t0 = std::chrono::steady_clock::now();
  l.start_real_time(threads);
  std::this_thread::sleep_for(std::chrono::duration<double>(std::min(seconds, 1.0)));
  const RealTimeCounts first = RealTimeCounts::of(l);
  if (seconds > 1.0) std::this_thread::sleep_for(std::chrono::duration<double>(seconds - 1.0));
  l.stop();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  getrusage(RUSAGE_SELF, &after);
  const auto cpu_s = [](const rusage& r) {
    return double(r.ru_utime.tv_sec + r.ru_stime.tv_sec) + double(r.ru_utime.tv_usec + r.ru_stime.tv_usec) * 1e-6;
  };
  const RealTimeCounts all = RealTimeCounts::of(l);
  std::printf("cells %zu\nthreads %u\nwall_s %.2f\nscans_expected %.0f\n", n, threads, wall, double(n) * wall * 1000.0);
  all.print("", RealTimeCounts{});
  all.print("steady_", first);
  std::printf("wake_latency_mean_us %.1f\nwake_latency_max_us %.1f\ncpu_cores_used %.3f\n",
              all.scans ? all.wake_sum_ns / double(all.scans) / 1000.0 : 0.0, double(all.wake_max_ns) / 1000.0,
              (cpu_s(after) - cpu_s(before)) / wall);
  return 0;
}

// --first-scans N: the chain of N cells' first four instants, each timed: what a cell's
// first scans cost beside its later ones (a line started in real time meets them all at once).
int first_scans(size_t n) {
  line::Line l(line_file(n, true));
  l.run();
  for (int k = 0; k < 4; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    l.scan_at(uint64_t(k) * 1000);
    const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    std::printf("scan %d: %.1f us per cell\n", k, us / double(n));
  }
  return 0;
}

int main(int argc, char** argv) {
  if (argc == 3 && std::strcmp(argv[1], "--first-scans") == 0) return first_scans(size_t(std::atol(argv[2])));
  if (argc == 5 && std::strcmp(argv[1], "--real-time") == 0)
    return real_time(size_t(std::atol(argv[2])), unsigned(std::atoi(argv[3])), std::atof(argv[4]));
  if (argc == 3 && std::strcmp(argv[1], "--memory") == 0) {
    const size_t n = size_t(std::atol(argv[2]));
    const std::string path = line_file(n, true);
    const double rss = resident_bytes(), heap = heap_bytes();
    line::Line l(path);
    l.run();
    for (uint64_t t = 0; t < 1000000; t += 1000) l.scan_at(t);  // one virtual second: every page touched
    std::printf("cells %zu\nresident_bytes_per_cell %.0f\nheap_bytes_per_cell %.0f\n", n,
                (resident_bytes() - rss) / double(n), (heap_bytes() - heap) / double(n));
    return 0;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
