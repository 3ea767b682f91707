#include "plc_cell/hsc/count_rule.h"

namespace plc_cell {
namespace hsc {

namespace {
// Quadrature state 0..3 in the forward order (A leads B): (1,0) (1,1) (0,1) (0,0).
int phase(Pins p) { return p.a ? (p.b ? 1 : 0) : (p.b ? 2 : 3); }
}  // namespace

int count_delta(Mode m, Pins s, Pins t) {
  const bool a_up = !s.a && t.a, a_down = s.a && !t.a;
  const bool b_up = !s.b && t.b, b_down = s.b && !t.b;
  switch (m) {
    case Mode::UD: return int(a_up) - int(b_up);
    case Mode::UDx2: return int(a_up || a_down) - int(b_up || b_down);
    case Mode::PR: return a_up ? (t.b ? -1 : 1) : 0;     // R sampled at the P edge
    case Mode::PRx2: return (a_up || a_down) ? (t.b ? -1 : 1) : 0;
    default: break;
  }
  const int step = (phase(t) - phase(s) + 4) % 4;
  if (step != 1 && step != 3) return 0;  // no change, or an illegal double change
  const int sign = step == 1 ? 1 : -1;   // forward: A ahead of B
  switch (m) {
    case Mode::AB:  // +1 on A rising with A ahead, -1 on A falling with A behind
      return (sign > 0 && a_up) || (sign < 0 && a_down) ? sign : 0;
    case Mode::ABx2: return (a_up || a_down) ? sign : 0;
    case Mode::ABx3: return (a_up || a_down || (sign > 0 && b_up) || (sign < 0 && b_down)) ? sign : 0;
    default: return sign;  // ABx4: every edge
  }
}

}  // namespace hsc
}  // namespace plc_cell
