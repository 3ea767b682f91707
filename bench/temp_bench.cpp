// Cost of 64 temperature channels and 16 FUN86 PID loops against a 1 ms scan.
// The FBs allows 32 temperature points per PLC, so the load is two PLCs, each with
// 2 x FBs-16TC (32 K thermocouples on thermal plants) and FUN86 over 8 points;
// every plant heater is a PWM output. The baseline is the same two PLCs scanning
// the same program without the modules and without FUN86.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/plc.h"
#include "plc_cell/sim/soft_cell.h"
#include "plc_cell/temp/temperature_cell.h"

namespace {

using namespace plc_cell;

std::string cell_yaml() {
  std::string y = "modules:\n  temperature:\n    modules:\n";
  for (int m = 0; m < 2; ++m) {
    y += "      - type: 16TC\n        sensor: K\n        channels:\n";
    for (int c = 0; c < 16; ++c)
      y += "          - {name: t" + std::to_string(16 * m + c) + ", plant: p" + std::to_string((16 * m + c) % 8) + "}\n";
  }
  y += "  plants:\n";
  for (int p = 0; p < 8; ++p)
    y += "    - {name: p" + std::to_string(p) + ", gain: 300, time_constant: 600, dead_time: 10, heater: Y" +
         std::to_string(p) + "}\n";
  return y;
}

const char* kWithPid =
    "ORG M1924\nMOV S=2000 D=R100\nMOV S=2000 D=R101\nMOV S=2000 D=R102\nMOV S=2000 D=R103\n"
    "MOV S=2000 D=R104\nMOV S=2000 D=R105\nMOV S=2000 D=R106\nMOV S=2000 D=R107\n"
    "ORG M1925\nLD M1925\n"
    "FUN 86 Md=0 Yn=Y0 Sn=0 Zn=8 Sv=R100 Os=R110 PR=R120 IR=R130 DR=R140 OR=R200 WR=R300 ERR=M100 ALM=M101\n"
    "END\n";
const char* kBaseline = "ORG M1924\nMOV S=2000 D=R100\nORG M1925\nOUT M1\nEND\n";

struct Rig {
  Plc plc{SoftCell::functions()};
  std::unique_ptr<temp::TemperatureCell> cell;
  Rig(bool with_temp) {
    plc.locked([&](ScanEngine& e, Memory& m) {
      if (with_temp) {
        cell = temp::make_temperature_cell(YAML::Load(cell_yaml()), "bench.yaml", m);
        e.add_hook(cell.get());
      }
      return 0;
    });
    plc.load_program_text(with_temp ? kWithPid : kBaseline, "bench.il");
    plc.set_mode(RunMode::Run);
  }
  ~Rig() {
    plc.locked([&](ScanEngine& e, Memory&) {
      if (cell) e.remove_hook(cell.get());
      return 0;
    });
  }
};

// One iteration = one 1 ms scan of both PLCs.
void run(benchmark::State& state, bool with_temp) {
  Rig a(with_temp), b(with_temp);
  uint64_t t = 0;
  for (int k = 0; k < 10000; ++k, t += 1000) a.plc.scan(t), b.plc.scan(t);  // past the first full read
  for (auto _ : state) {
    a.plc.scan(t);
    b.plc.scan(t);
    t += 1000;
  }
}

void BM_TwoPlcs_Baseline(benchmark::State& s) { run(s, false); }
void BM_TwoPlcs_64Channels_16Pid(benchmark::State& s) { run(s, true); }
BENCHMARK(BM_TwoPlcs_Baseline);
BENCHMARK(BM_TwoPlcs_64Channels_16Pid);

}  // namespace

BENCHMARK_MAIN();
