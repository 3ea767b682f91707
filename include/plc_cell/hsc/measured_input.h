#pragma once
// The pulse measurement of one of X0-X15 (counters.pulse_measurement) as a part of the
// counters' unit. Explicit edges reach its meter as they act; an analytic pin's edges
// are found from the quarters crossed (at most the last two cycles of a span matter, so
// the cost does not depend on the frequency).
#include <cstdint>

#include "plc_cell/hsc/component.h"
#include "plc_cell/hsc/input_pins.h"
#include "plc_cell/hsc/pulse_meter.h"
#include "plc_cell/hsc/unit_context.h"

namespace plc_cell {
namespace hsc {

class MeasuredInput final : public Component {
 public:
  MeasuredInput(UnitContext& ctx, const InputPins& pins, int x, uint64_t timeout_ns)
      : ctx_(ctx), pins_(pins), x_(x), meter_(timeout_ns) {}

  int input() const { return x_; }
  PulseReading read() const { return meter_.read(ctx_.now()); }

  void start(uint64_t t_ns) override;
  void settle() override;
  void advance_to(uint64_t t_ns) override;
  void input_edges(uint64_t t_ns, const InputLevels& before, const InputLevels& after) override;

 private:
  UnitContext& ctx_;
  const InputPins& pins_;
  int x_;
  PulseMeter meter_;
  const EdgeSource* src_ = nullptr;  // the analytic driver the quarter q_ belongs to
  int64_t q_ = 0;
  bool level_ = false;               // at q_
  uint64_t epoch_ = 0;
};

}  // namespace hsc
}  // namespace plc_cell
