#pragma once
// What the parts of the counters' unit share: the PLC's engine and memory, the cell's
// clock and interrupts, and the observers of CV=PV matches.
#include <cstdint>
#include <functional>
#include <vector>

#include "plc_cell/core/memory.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/timeline/scheduler.h"

namespace plc_cell {
namespace hsc {

// Every CV=PV match of counter n (HSC0-7; timer: HST0-3) at its instant.
using MatchObserver = std::function<void(uint64_t t_ns, int n, bool timer)>;

struct UnitContext {
  ScanEngine& engine;
  Memory& mem;
  timeline::Scheduler& sched;
  std::vector<MatchObserver> match_obs;

  uint64_t now() const { return sched.now_ns(); }
  bool running() const { return sched.running(); }
  timeline::InterruptController& irq() const { return sched.interrupts(); }
  // The interrupt is requested; the observers see the match whether or not a routine runs.
  void match(int source, int n, bool timer, uint64_t t_ns) {
    sched.raise(source);
    for (auto& f : match_obs) f(t_ns, n, timer);
  }
  uint32_t reg32(uint32_t r) const { return uint32_t(mem.reg(Area::R, r)) | (uint32_t(mem.reg(Area::R, r + 1)) << 16); }
  void set_reg32(uint32_t r, uint32_t v) {
    mem.set_reg(Area::R, r, static_cast<uint16_t>(v));
    mem.set_reg(Area::R, r + 1, static_cast<uint16_t>(v >> 16));
  }
};

}  // namespace hsc
}  // namespace plc_cell
