#pragma once
// The external interrupts on the edges of X0-X15 (counters.interrupts, manual §9.5): an
// edge interrupts only if configured with a routine. Explicit edges request it as they
// act; the edges of an analytic source are found from its quarters.
#include <array>
#include <cstdint>
#include <vector>

#include "plc_cell/hsc/component.h"
#include "plc_cell/hsc/input_pins.h"
#include "plc_cell/hsc/unit_context.h"

namespace plc_cell {
namespace hsc {

class EdgeInterrupts final : public Component {
 public:
  // edges: 2*x + (falling ? 1 : 0), as HscConfig::edge_interrupts.
  EdgeInterrupts(UnitContext& ctx, const InputPins& pins, std::vector<int> edges);

  uint64_t next_event_ns() override;
  void at(uint64_t t_ns) override;
  void input_edges(uint64_t t_ns, const InputLevels& before, const InputLevels& after) override;

 private:
  UnitContext& ctx_;
  const InputPins& pins_;
  std::vector<int> edges_;
  std::array<bool, 32> configured_{};
  std::array<uint64_t, 32> next_{};  // what next_event_ns() found for each edge
};

}  // namespace hsc
}  // namespace plc_cell
