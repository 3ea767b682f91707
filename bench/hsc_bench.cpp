// High-speed counter benchmark: four A/B x4 encoders (HSC0-HSC3) at up to 460 kHz
// per phase (1.84 M counts/s each). One iteration = one 1 ms scan of a small
// program that reads all four counters (FUN92). The counts between scans are
// computed analytically, so the cost per scan must not grow with the frequency.
// A second family adds a CV=PV interrupt every 10 ms per counter (the ISR moves PV
// on), to show the cost of events: it grows with the event rate, not the input rate.
#include <benchmark/benchmark.h>
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "plc_cell/core/plc.h"
#include "plc_cell/sim/soft_cell.h"
#include "plc_cell/hsc/hsc_unit.h"

namespace {

using plc_cell::Plc;
using plc_cell::RunMode;
using plc_cell::hsc::HscUnit;

std::string cell_yaml(int64_t hz) {
  std::string y = "counters:\n";
  for (int n = 0; n < 4; ++n) y += "  hsc" + std::to_string(n) + ": {mode: MD7}\n";
  y += "  sources:\n";
  const int pins[4] = {0, 4, 8, 12};
  for (int n = 0; n < 4; ++n)
    y += "    - {name: enc" + std::to_string(n) + ", type: encoder, a: X" + std::to_string(pins[n]) +
         ", hz: " + std::to_string(hz) + "}\n";
  return y;
}

std::string program(bool isr, int64_t hz) {
  std::string p = "ORG M1925\n";
  for (int n = 0; n < 4; ++n) p += "FUN 92 HSCTR CN=" + std::to_string(n) + "\n";
  if (!isr) return p + "END\n";
  // PV every 10 ms of counting: 4 * hz / 100 counts.
  const std::string step = std::to_string(4 * hz / 100);
  std::string init = "ORG M1924\n";
  for (int n = 0; n < 4; ++n) {
    const std::string pv = "DR" + std::to_string(4098 + 4 * n);
    init += "FUN 8D MOV S=" + step + " D=" + pv + "\nFUN 93 CN=" + std::to_string(n) + " D=1\n";
  }
  p = init + p + "END\n";
  for (int n = 0; n < 4; ++n) {
    const std::string pv = "DR" + std::to_string(4098 + 4 * n);
    p += "LBL HSC" + std::to_string(n) + "I\nORG M1925\nFUN 11D ADD Sa=" + pv + " Sb=" + step + " D=" + pv +
         "\nFUN 93 CN=" + std::to_string(n) + " D=1\nRTI\n";
  }
  return p;
}

void run(benchmark::State& state, bool isr) {
  const int64_t hz = state.range(0);
  Plc plc{plc_cell::SoftCell::functions()};  // the cell's instruction set: FUN140-143 and the HSC FUNs
  HscUnit unit(plc, plc_cell::hsc::parse_hsc_config(YAML::Load(cell_yaml(hz))["counters"], "bench.yaml"));
  plc.load_program_text(program(isr, hz), "bench.il");
  plc.set_mode(RunMode::Run);
  uint64_t now = 0;
  for (auto _ : state) {
    plc.scan(now);
    now += 1000;
  }
  const int64_t cv = plc.locked([&](plc_cell::ScanEngine&, plc_cell::Memory&) { return unit.count(0); });
  const int64_t expect = int64_t(4 * hz * ((now - 1000) / 1000)) / 1000;
  if (cv != expect) {
    std::fprintf(stderr, "HSC0 counted %lld, expected %lld\n", (long long)cv, (long long)expect);
    std::abort();
  }
  state.counters["counts_per_scan"] = double(4 * hz) / 1000.0 * 4;
}

void BM_FourEncodersPerScan(benchmark::State& state) { run(state, false); }
void BM_FourEncodersWithPvInterruptsPerScan(benchmark::State& state) { run(state, true); }

BENCHMARK(BM_FourEncodersPerScan)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(460000);
BENCHMARK(BM_FourEncodersWithPvInterruptsPerScan)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(460000);

}  // namespace

BENCHMARK_MAIN();
