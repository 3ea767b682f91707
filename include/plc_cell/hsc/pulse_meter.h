#pragma once
// Pulse measurement of one counter input (TRi FMD1616 Ch. 8: PULSEWIDTH, PULSEPERIOD,
// PULSEFREQUENCY): the ON time and the period of the last full cycle, taken at each
// rising edge from the exact edge instants, as a capture unit on the pin would.
//
// The manual says nothing of the first pulse or of a signal that stops; plc_cell's rule
// (docs/counters-and-interrupts.md "Pulse measurement"):
// * nothing is measured (all 0) until the second rising edge completes a first cycle;
// * all values are 0 once no rising edge has come for longer than the timeout (twice
//   the last period, or a configured time), and the next rising edge starts over as a
//   first edge.
#include <cstdint>

namespace plc_cell {
namespace hsc {

struct PulseReading {
  uint64_t width_ns = 0;   // ON time of the last full cycle
  uint64_t period_ns = 0;  // rising edge to rising edge
  double frequency_hz = 0;  // 1 / period
};

class PulseMeter {
 public:
  // timeout_ns 0: twice the last period (and none before a first period).
  explicit PulseMeter(uint64_t timeout_ns = 0) : timeout_ns_(timeout_ns) {}

  void reset();                          // RUN: nothing measured yet
  void edge(uint64_t t_ns, bool level);  // a level change of the input, in time order
  PulseReading read(uint64_t now_ns) const;

 private:
  bool expired(uint64_t now_ns) const;

  uint64_t timeout_ns_;
  bool have_rise_ = false, have_fall_ = false;
  uint64_t rise_ = 0, fall_ = 0;  // the last rising edge, and the falling edge after it
  uint64_t width_ = 0, period_ = 0;
};

}  // namespace hsc
}  // namespace plc_cell
