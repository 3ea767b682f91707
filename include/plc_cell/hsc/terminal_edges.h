#pragma once
// The explicit edges at the terminals of X0-X15, in time order: the cell simulation's
// scheduled edges and pulse trains, levels set from outside the simulation (a scenario,
// a ROS topic), and the digital input filter's delayed outputs. Something outside may
// mute the simulation of an input (mute()); the edges it would play are then dropped.
#include <cstdint>
#include <functional>
#include <queue>
#include <utility>
#include <vector>

#include "plc_cell/hsc/component.h"
#include "plc_cell/hsc/input_pins.h"
#include "plc_cell/hsc/pulse_train.h"
#include "plc_cell/hsc/unit_context.h"

namespace plc_cell {
namespace hsc {

class TerminalEdges final : public Component {
 public:
  TerminalEdges(UnitContext& ctx, InputPins& pins) : ctx_(ctx), pins_(pins) {}

  // An exact-time edge of the simulation (through x's filter).
  void schedule(int x, uint64_t t_ns, bool level);
  // Throws Error if x is not X0-X15 or an analytic source drives it.
  void add_train(int x, uint64_t period_ns, uint64_t width_ns, uint64_t delay_ns);
  void mute(int x, bool muted);
  bool simulates(int x) const { return x >= 0 && x < 16 && simulated_[x]; }
  // A level set outside the simulation since the last scan, at now.
  void external(int x, bool level) { edges_.push({ctx_.now(), seq_++, x, level}); }
  bool due(uint64_t t_ns) const { return !edges_.empty() && edges_.top().t <= t_ns; }

  void start(uint64_t t_ns) override { prev_ns_ = t_ns; }
  // Keeps the present instant for take(): the loop asks just before it moves the clock.
  uint64_t next_event_ns() override;
  // The edges acting at t after the filter: (input, level), in the order they come.
  std::vector<std::pair<int, bool>> take(uint64_t t_ns);

 private:
  struct Edge {
    uint64_t t;
    uint64_t seq;
    int x;
    bool level;
    bool commit = false;  // the filter's output: valid only if gen is still the pin's
    uint64_t gen = 0;
    bool simulated = false;  // from schedule(): muted with the pin
    bool operator>(const Edge& o) const { return t != o.t ? t > o.t : seq > o.seq; }
  };
  void filter(const Edge& e, std::vector<std::pair<int, bool>>* group);

  UnitContext& ctx_;
  InputPins& pins_;
  std::priority_queue<Edge, std::vector<Edge>, std::greater<Edge>> edges_;
  std::vector<PulseTrain> trains_;
  uint64_t seq_ = 0;
  uint64_t prev_ns_ = 0;                // the instant before the present one (pulse trains)
  std::array<bool, 16> simulated_{};    // scheduled edges or a pulse train play the pin
  std::array<bool, 16> muted_{};        // ... but something outside plays it now
  std::array<bool, 16> sim_raw_{};      // the raw level the scheduled edges gave, muted or not
};

}  // namespace hsc
}  // namespace plc_cell
