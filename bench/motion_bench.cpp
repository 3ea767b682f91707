// Pulse-output benchmark: four axes PSO0-PSO3 each running a FUN140 program at up to
// 921 600 Hz. One iteration = one 1 ms scan. Pulses are never generated one by one
// (closed-form profiles), so the cost per scan must not grow with the frequency.
// Family 1: endless rotation. Family 2: back-and-forth moves of 10 ms each (a step
// completion per axis every 10 ms): the cost grows with the step rate, not the pulse rate.
// Family 3: as 2 with 1 ms ramps, each axis's pins Y2n/Y2n+1 (U/D) wired back into
// HSC n (MD0): the counters count every pulse of the ramps edge-exactly (checked at
// the end) and their cost does not grow with the pulse rate either.
#include <benchmark/benchmark.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "plc_cell/core/plc.h"
#include "plc_cell/sim/soft_cell.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/motion/lin_table.h"
#include "plc_cell/motion/motion_unit.h"
#include "plc_cell/motion/table.h"

namespace {

using namespace plc_cell;
using motion::MotionUnit;

void run(benchmark::State& state, bool moves, bool looped = false) {
  const int64_t hz = state.range(0);
  Plc plc{plc_cell::SoftCell::functions()};  // the cell's instruction set: FUN140-143 and the HSC FUNs
  std::unique_ptr<hsc::HscUnit> counters;
  if (looped)  // HHSC n counts U on X(4n), D on X(4n+1)
    counters = std::make_unique<hsc::HscUnit>(
        plc, hsc::parse_hsc_config(YAML::Load("{hsc0: {mode: MD0, b: true}, hsc1: {mode: MD0, b: true}, "
                                              "hsc2: {mode: MD0, b: true}, hsc3: {mode: MD0, b: true}}"),
                                   "bench.yaml"));
  MotionUnit unit(plc);
  if (looped)
    unit.configure(motion::parse_axes_config(
        YAML::Load("{pso0: {output: UD, wiring: {Y0: X0, Y1: X1}}, pso1: {output: UD, wiring: {Y2: X4, Y3: X5}}, "
                   "pso2: {output: UD, wiring: {Y4: X8, Y5: X9}}, pso3: {output: UD, wiring: {Y6: X12, Y7: X13}}}"),
        "bench.yaml"));
  std::string il;
  for (int n = 0; n < 4; ++n)
    il += "ORG M1925\nLD M1000\nLD M1001\nHSPSO Ps=" + std::to_string(n) + " SR=R" + std::to_string(100 * n) + " WR=R" +
          std::to_string(1000 + 10 * n) + "\n";
  plc.load_program_text(il + "END\n", "bench.il");
  plc.set_mode(RunMode::Run);
  const std::string n_pulses = std::to_string(hz / 100);
  const std::string text = moves ? "SPD " + std::to_string(hz) + "\nDRV ADR,+," + n_pulses + ",Ps\nGOTO NEXT\nSPD " +
                                       std::to_string(hz) + "\nDRV ADR,-," + n_pulses + ",Ps\nGOTO 1\nMEND\n"
                                 : "SPD " + std::to_string(hz) + "\nDRV ADR,+,0,Ps\nGOTO NEXT\nMEND\n";
  motion::Table t;
  motion::TableError e;
  if (!motion::parse_table(text, &t, &e)) std::abort();
  const auto regs = motion::encode_table(t);
  plc.locked([&](ScanEngine&, Memory& m) {
    for (int n = 0; n < 4; ++n) {
      motion::AxisParams p;
      p.p4_max = 921600;
      p.p8_acc_ms = looped ? 1 : 0;  // square profile: the position is hz * t exactly
      unit.set_params(n, p);
      for (size_t i = 0; i < regs.size(); ++i) m.set_reg(Area::R, 100 * n + i, regs[i]);
    }
    return 0;
  });
  uint64_t now = 0;
  for (auto _ : state) {
    plc.scan(now);
    now += 1000;
  }
  const int64_t pos = plc.locked([&](ScanEngine&, Memory&) { return unit.position(0); });
  const int64_t elapsed_us = int64_t(now - 1000);
  const int64_t expect = moves ? -1 : hz * elapsed_us / 1000000;
  if (!moves && (pos < expect - 1 || pos > expect)) {
    std::fprintf(stderr, "PSO0 at %lld, expected %lld\n", (long long)pos, (long long)expect);
    std::abort();
  }
  if (looped) {
    for (int n = 0; n < 4; ++n) {
      const int64_t cv = plc.locked([&](ScanEngine&, Memory&) { return counters->count(n); });
      // Pulses whose leading edge is out (the counter counts there, half a pulse
      // before the pulse instant that pulse_count() uses).
      const int64_t sent = plc.locked([&](ScanEngine&, Memory&) {
        const motion::Axis& a = unit.axis(n);
        return a.moving() ? a.count0() + (a.forward() ? 1 : -1) * a.committed(unit.now_ns()) : a.pulse_count(0);
      });
      if (cv != sent) {
        std::fprintf(stderr, "HSC%d counted %lld of %lld pulses\n", n, (long long)cv, (long long)sent);
        std::abort();
      }
    }
  }
  state.counters["pulses_per_scan"] = double(hz) / 1000.0 * 4;
}

// Family 3: one FUN147 interpolating all four axes, a step (there and back) every
// 10 ms, the lead axis at hz: the cost per scan of a 4-axis interpolation.
void BM_FourAxisInterpolationStepEvery10ms(benchmark::State& state) {
  const int64_t hz = state.range(0);
  Plc plc{plc_cell::SoftCell::functions()};  // the cell's instruction set: FUN140-143 and the HSC FUNs
  MotionUnit unit(plc);
  plc.load_program_text("ORG M1925\nLD M1000\nLD M1001\nMHSP0 Gp=0 SR=R0 WR=R1000\nEND\n", "bench.il");
  plc.set_mode(RunMode::Run);
  // |s| = sqrt(1 + 1/4 + 1/9 + 1/16) = 1.193 x the lead stroke: SPD = 1.193 hz puts
  // the lead axis at hz for 10 ms.
  const int64_t n = hz / 100;
  const std::string s = std::to_string(n) + "," + std::to_string(n / 2) + "," + std::to_string(n / 3) + "," +
                        std::to_string(n / 4);
  const std::string back = "-" + std::to_string(n) + ",-" + std::to_string(n / 2) + ",-" + std::to_string(n / 3) +
                           ",-" + std::to_string(n / 4);
  const std::string v = std::to_string(std::min<int64_t>(921600, hz * 1193 / 1000));
  motion::LinTable t;
  motion::TableError e;
  if (!motion::parse_lin_table("SPD " + v + "\nLIN ADR," + s + ",Ps\nGOTO NEXT\nSPD " + v + "\nLIN ADR," + back +
                                   ",Ps\nGOTO 1\nMEND\n",
                               &t, &e))
    std::abort();
  const auto regs = motion::encode_lin_table(t);
  plc.locked([&](ScanEngine&, Memory& m) {
    for (int a = 0; a < 4; ++a) {
      motion::AxisParams p;
      p.p4_max = 921600;
      p.p13_interp_ms = 0;  // square profile
      unit.set_params(a, p);
    }
    for (size_t i = 0; i < regs.size(); ++i) m.set_reg(Area::R, static_cast<uint32_t>(i), regs[i]);
    return 0;
  });
  uint64_t now = 0;
  for (auto _ : state) {
    plc.scan(now);
    now += 1000;
  }
  state.counters["pulses_per_scan"] = double(hz) / 1000.0 * (1 + 0.5 + 0.33 + 0.25);
}
BENCHMARK(BM_FourAxisInterpolationStepEvery10ms)->Arg(1000)->Arg(20000)->Arg(460000)->Arg(772000);

void BM_FourAxesEndless(benchmark::State& state) { run(state, false); }
void BM_FourAxesStepEvery10ms(benchmark::State& state) { run(state, true); }
void BM_FourAxesLoopedIntoCounters(benchmark::State& state) { run(state, true, true); }

BENCHMARK(BM_FourAxesEndless)->Arg(1000)->Arg(20000)->Arg(460000)->Arg(921600);
BENCHMARK(BM_FourAxesStepEvery10ms)->Arg(1000)->Arg(20000)->Arg(460000)->Arg(921600);
BENCHMARK(BM_FourAxesLoopedIntoCounters)->Arg(1000)->Arg(20000)->Arg(460000)->Arg(921600);

}  // namespace

BENCHMARK_MAIN();
