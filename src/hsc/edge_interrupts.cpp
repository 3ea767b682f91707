#include "plc_cell/hsc/edge_interrupts.h"

#include <algorithm>

#include "plc_cell/core/interrupt_sources.h"

namespace plc_cell {
namespace hsc {

EdgeInterrupts::EdgeInterrupts(UnitContext& ctx, const InputPins& pins, std::vector<int> edges)
    : ctx_(ctx), pins_(pins), edges_(std::move(edges)) {
  for (int e : edges_) configured_[e] = true;
  next_.fill(kNever);
}

uint64_t EdgeInterrupts::next_event_ns() {
  uint64_t t = kNever;
  next_.fill(kNever);
  for (int e : edges_) {
    const InputPin& p = pins_[e / 2];
    if (!p.src || !ctx_.irq().present(irq::kX0Up + e) || !ctx_.irq().enabled(irq::kX0Up + e)) continue;
    next_[e] = p.next_source_edge(e % 2 == 0, ctx_.now());
    t = std::min(t, next_[e]);
  }
  return t;
}

void EdgeInterrupts::at(uint64_t t) {
  for (int e = 0; e < 32; ++e)
    if (next_[e] == t) ctx_.sched.raise(irq::kX0Up + e);
}

void EdgeInterrupts::input_edges(uint64_t, const InputLevels& before, const InputLevels& after) {
  for (int x = 0; x < 16; ++x)
    if (before[x] != after[x] && configured_[2 * x + (after[x] ? 0 : 1)]) ctx_.sched.raise(irq::x_edge_source(x, !after[x]));
}

}  // namespace hsc
}  // namespace plc_cell
