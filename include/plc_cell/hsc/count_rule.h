#pragma once
// The counting rule of modes MD0-MD7 (manual §10.2): how one change of the
// counting inputs moves CV. Explicit edges and the analytic sources both use it,
// so a hand-made edge list and a 460 kHz encoder count by the same rule.
#include <cstdint>

namespace plc_cell {
namespace hsc {

enum class Mode : uint8_t { UD = 0, UDx2, PR, PRx2, AB, ABx2, ABx3, ABx4 };

inline bool is_ab(Mode m) { return m >= Mode::AB; }

// Levels (after polarity) of the two counting inputs: a = U/P/A, b = D/R/B.
struct Pins {
  bool a = false, b = false;
};

// CV change for the transition before -> after. In P/R modes b is the direction R
// (the R input, or the software relay when there is none): R = 1 counts down.
// Simultaneous U and D rising edges cancel (MD0). An A/B transition that changes
// both phases at once is illegal and counts 0 (AMBIG-5; docs/counters-and-interrupts.md).
int count_delta(Mode m, Pins before, Pins after);

}  // namespace hsc
}  // namespace plc_cell
