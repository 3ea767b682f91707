// plc_cell test's speed in virtual seconds per wall second, side by side with its peer:
// `plc_cell sim` (VirtualRun) running the same cell for the same virtual time. Two cells:
// the demo conveyor (27 instructions) for 10 minutes, and a generated 12,001-instruction
// program for 1 minute. Each iteration builds a fresh cell, as both tools do.
//   .build/ws/devel/lib/plc_cell/bench_scenario   (docs/performance.md, "Scenario tests")
#include <benchmark/benchmark.h>

#include <fstream>
#include <string>

#include "plc_cell/runtime/cell.h"
#include "plc_cell/scenario/cell_target.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/scenario_file.h"
#include "plc_cell/sim/virtual_run.h"

namespace {

using namespace plc_cell;

const std::string kDemo = std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/conveyor.yaml";

// 4000 networks, 12,001 instructions: contacts on inputs and relays, a coil, and a MOV or
// ADD every other network, so that the program both branches and computes.
std::string large_cell() {
  const std::string dir = "/tmp/plc_cell_bench_scenario";
  (void)std::system(("mkdir -p " + dir).c_str());
  std::ofstream il(dir + "/large.il");
  for (int n = 0; n < 2000; ++n) {
    il << "ORG X" << n % 64 << "\nAND NOT M" << (n + 7) % 1500 << "\nOR M" << n % 1500 << "\nOUT M" << (n + 1) % 1500
       << "\n";
    if (n % 2) il << "ORG M1925\nFUN 11 Sa=R" << n % 1000 << " Sb=1 D=R" << n % 1000 << "\n";
    else il << "ORG M1925\nMOV S=R" << n % 1000 << " D=R" << (n + 1) % 1000 << "\n";
  }
  il << "END\n";
  std::ofstream(dir + "/large.yaml") << "cell: {name: large, program: large.il}\n"
                                        "plc: {scan_period: 0.001}\n"
                                        "simulation:\n"
                                        "  inputs:\n"
                                        "    X0: {pulse: {period: 0.1, width: 0.05, delay: 0}}\n"
                                        "    X1: {pulse: {period: 0.5, width: 0.2, delay: 0.1}}\n";
  return dir + "/large.yaml";
}

scenario::Case one_case(const std::string& cell, const std::string& steps) {
  const scenario::Scenario sc =
      scenario::parse_scenario("cell: " + cell + "\ncases:\n  - name: c\n    steps:\n" + steps, "/tmp/bench.yaml");
  return sc.cases.at(0);
}

void report(benchmark::State& state, double virtual_s) {
  state.counters["virtual_s_per_s"] =
      benchmark::Counter(virtual_s * double(state.iterations()), benchmark::Counter::kIsRate);
}

// The demo's ten minutes, checked at every scan (line_running stays on) and at the end
// (120 parts: one every 5 s from 1 s, counted 2.5 s after it arrives).
void BM_Demo_Test(benchmark::State& state) {
  const scenario::Case c = one_case(kDemo,
                                    "      - at: 0s\n"
                                    "        expect: line_running\n"
                                    "        stays: 600s\n"
                                    "      - expect: R0 == 120\n");
  for (auto _ : state) {
    scenario::CellTarget t(kDemo, "");
    const scenario::CaseResult r = scenario::run_case(c, t);
    if (!r.passed) state.SkipWithError(r.failure.c_str());
  }
  report(state, 600);
}

void BM_Demo_Sim(benchmark::State& state) {
  for (auto _ : state) {
    Cell cell(kDemo, {}, Cell::Purpose::Simulate);
    cell.plc().set_mode(RunMode::Run);
    VirtualRun run(cell.plc(), cell.scan_period_us());
    run.watch(parse_address("M0"));
    run.watch(parse_address("R0"));
    run.run_for(600000000);
    if (run.values()[1] != 120) state.SkipWithError("the demo did not count 120 parts");
  }
  report(state, 600);
}

void BM_Large_Test(benchmark::State& state) {
  const std::string cell = large_cell();
  const scenario::Case c = one_case(cell,
                                    "      - expect: R0 >= 0\n"
                                    "        stays: 60s\n");
  for (auto _ : state) {
    scenario::CellTarget t(cell, "");
    const scenario::CaseResult r = scenario::run_case(c, t);
    if (!r.passed) state.SkipWithError(r.failure.c_str());
  }
  report(state, 60);
}

void BM_Large_Sim(benchmark::State& state) {
  const std::string path = large_cell();
  for (auto _ : state) {
    Cell cell(path, {}, Cell::Purpose::Simulate);
    cell.plc().set_mode(RunMode::Run);
    VirtualRun run(cell.plc(), cell.scan_period_us());
    run.watch(parse_address("R0"));
    run.run_for(60000000);
    benchmark::DoNotOptimize(run.values());
  }
  report(state, 60);
}

// Interleaved, so that both sides of a pair see the same machine load.
BENCHMARK(BM_Demo_Sim)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Demo_Test)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Large_Sim)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_Large_Test)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
