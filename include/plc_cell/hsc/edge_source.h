#pragma once
// What drives the counting inputs of the high-speed counters in the simulated cell:
// a signal whose two phases are functions of a quarter index Q(t), exact in virtual
// time. The counters never sample it; they ask when Q reaches a value and count the
// boundaries crossed with the counting rule, so their cost does not depend on the
// frequency (docs/counters-and-interrupts.md "Edge sources").
//
// Two implementations: PulseSource (a constant-rate encoder or pulse generator) and
// motion::AxisEdgeSource (a pulse-output axis: its output pins wired back to inputs,
// or an encoder on its load; the rate follows the axis's ramps).
#include <cstdint>
#include <string>

namespace plc_cell {
namespace hsc {

class EdgeSource {
 public:
  virtual ~EdgeSource() = default;
  virtual const std::string& name() const = 0;
  // Quarter index at t (t at or after the last change). Between two changes Q moves
  // monotonically in direction() and the phase levels are 4-periodic in Q.
  virtual int64_t quarter(uint64_t t_ns) const = 0;
  virtual int direction() const = 0;  // +1, -1, or 0 when Q does not move
  // First instant >= from_ns at which Q reaches q (moving in direction());
  // UINT64_MAX if it does not in the present state.
  virtual uint64_t time_of_quarter(int64_t q, uint64_t from_ns) const = 0;
  // Level of phase 0 (A, or the first pin) or 1 (B, the second pin) at quarter q.
  virtual bool level(int phase, int64_t q) const = 0;
  // Highest period rate (Hz) in the present state: the input filter's test.
  virtual double rate_hz() const = 0;
  // Changes whenever the source changes in a way the quarter index does not show
  // (an axis starts, cuts or ends a move): the counters then take the levels before
  // and after as one transition (a real edge if a pin changed).
  virtual uint64_t epoch() const { return 0; }
};

}  // namespace hsc
}  // namespace plc_cell
