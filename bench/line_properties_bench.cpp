// What watching a line's properties costs its scans (docs/performance.md, "Lines of
// cells"): the example line (3 cells) run 60 virtual seconds on one clock, with and without
// the watcher of its scenario file's two properties, CPU time per instant, 5 runs each,
// interleaved; the median is printed.
//   .build/ws/devel/lib/plc_cell/bench_line_properties
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <vector>

#include "plc_cell/line/line.h"
#include "plc_cell/line/line_properties.h"
#include "plc_cell/scenario/scenario_file.h"

namespace {

using namespace plc_cell;

const std::string kDir = std::string(PLC_CELL_SOURCE_DIR) + "/examples/line/";

double cpu_s() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
}

// ns of CPU per instant of the line over 60 s of 1 ms instants.
double run(bool watched) {
  line::Line l(kDir + "line.line.yaml");
  if (watched) {
    const scenario::Scenario sc = scenario::load_scenario(kDir + "line.scenario.yaml");
    line::watch_properties(l, std::make_shared<scenario::PropertyWatcher>(
                                  sc.properties,
                                  [&l](const scenario::Probe& p) {
                                    const size_t i = size_t(l.find(p.cell));
                                    return scenario::WatchedAddress{i, l.cell(i)->config().resolve(p.name)};
                                  },
                                  "line.scenario.yaml", "bench"));
  }
  l.run();
  const uint64_t instants = 60000;
  const double t0 = cpu_s();
  for (uint64_t k = 0; k < instants; ++k) l.scan_at(k * l.tick_us());
  return (cpu_s() - t0) * 1e9 / double(instants);
}

}  // namespace

int main() {
  std::vector<double> bare, watched;
  for (int i = 0; i < 5; ++i) {
    bare.push_back(run(false));
    watched.push_back(run(true));
  }
  std::sort(bare.begin(), bare.end());
  std::sort(watched.begin(), watched.end());
  std::printf("example line, ns of CPU per instant (median of 5): without properties %.0f, watched %.0f (%+.0f)\n",
              bare[2], watched[2], watched[2] - bare[2]);
  return 0;
}
