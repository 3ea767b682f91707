#pragma once
// A soft PLC with its high-speed unit on a virtual clock: every output change and
// every ISR start is logged with its virtual instant (ns).
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/plc.h"
#include "plc_cell/sim/soft_cell.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/timeline/scheduler.h"

namespace plc_cell {
namespace hsc {

struct OutputChange {
  uint64_t t_ns;
  uint32_t y;
  bool level;
};
struct IsrRun {
  uint64_t t_ns;
  int source;
  int64_t cv[8];
  int depth;  // nesting level of this routine: 1 = interrupted the main program
};

class HscCell {
 public:
  HscCell(const std::string& yaml, const std::string& il,
          FunctionTable table = SoftCell::functions())
      : plc(std::move(table)) {
    const YAML::Node doc = YAML::Load(yaml);
    unit = std::make_unique<HscUnit>(plc, parse_hsc_config(doc["counters"], "cell.yaml"));
    unit->on_output([this](uint64_t t, uint32_t y, bool v) { outputs.push_back({t, y, v}); });
    sched = plc.locked([](ScanEngine& e, Memory&) { return &timeline::Scheduler::of(e); });
    sched->on_isr([this](uint64_t t, int s) {
      IsrRun r{t, s, {}, sched->interrupts().depth()};
      for (int n = 0; n < 8; ++n) r.cv[n] = unit->count(n);
      isrs.push_back(r);
    });
    plc.load_program_text(il, "test.il");
    EXPECT_TRUE(plc.set_mode(RunMode::Run));
  }
  // Scans at now, now + period, ... for duration_us.
  void run(uint64_t duration_us, uint64_t period_us = 1000) {
    const uint64_t end = now_us + duration_us;
    while (now_us < end) {
      plc.scan(now_us);
      now_us += period_us;
    }
  }
  template <typename F>
  auto with(F&& f) {
    return plc.locked([&](ScanEngine&, Memory&) { return f(*unit); });
  }
  uint32_t get(const std::string& a) { return plc.read(parse_address(a), 1).at(0); }
  void put(const std::string& a, uint32_t v) { plc.write(parse_address(a), {v}); }
  std::vector<OutputChange> changes_of(uint32_t y) const {
    std::vector<OutputChange> r;
    for (const auto& c : outputs)
      if (c.y == y) r.push_back(c);
    return r;
  }
  std::vector<IsrRun> runs_of(int source) const {
    std::vector<IsrRun> r;
    for (const auto& i : isrs)
      if (i.source == source) r.push_back(i);
    return r;
  }

  Plc plc;
  std::unique_ptr<HscUnit> unit;
  timeline::Scheduler* sched = nullptr;  // the cell's clock and interrupt system
  std::vector<OutputChange> outputs;
  std::vector<IsrRun> isrs;
  uint64_t now_us = 0;
};

}  // namespace hsc
}  // namespace plc_cell
