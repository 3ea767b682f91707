#include "plc_cell/hsc/decoding.h"

namespace plc_cell {
namespace hsc {

namespace {
struct Named {
  Decoding d;
  const char* name;
};
constexpr Named kNames[] = {{Decoding::Simple, "simple"}, {Decoding::Enhanced, "enhanced"},
                            {Decoding::X1, "x1"},         {Decoding::X2, "x2"},
                            {Decoding::X4, "x4"}};
}  // namespace

bool decoding_from_name(const std::string& name, Decoding* d) {
  for (const auto& n : kNames)
    if (name == n.name) {
      *d = n.d;
      return true;
    }
  return false;
}

const char* decoding_name(Decoding d) {
  for (const auto& n : kNames)
    if (n.d == d) return n.name;
  return "";
}

int decode_delta(Mode m, Decoding d, DecodeState* s, Pins t0, Pins t1) {
  const bool a_changed = t0.a != t1.a, b_changed = t0.b != t1.b;
  const DecodeState was = *s;
  if (a_changed && b_changed) s->last = -1;  // a double change: the decoder loses the thread
  else if (a_changed) s->last = 0;
  else if (b_changed) s->last = 1;
  switch (d) {
    case Decoding::Fatek: return count_delta(m, t0, t1);
    // x1/x2/x4 are the quadrature multipliers the FATEK modes already have:
    // 1 count per cycle at one edge of A, both edges of A, every edge.
    case Decoding::X1: return count_delta(Mode::AB, t0, t1);
    case Decoding::X2: return count_delta(Mode::ABx2, t0, t1);
    case Decoding::X4: return count_delta(Mode::ABx4, t0, t1);
    default: break;
  }
  if (a_changed == b_changed) return 0;  // nothing moved, or an illegal double change
  // Simple: a pulse is its rising edge; A rising while B is OFF counts up (A leads B,
  // or B is not there), B rising while A is OFF counts down. Both count edges leave
  // the state "both OFF", so the rule is one count per quadrature cycle.
  int delta = 0;
  if (a_changed && t1.a && !t0.b) delta = 1;
  if (b_changed && t1.b && !t0.a) delta = -1;
  // Enhanced: the same edges count only if the decoder entered "both OFF" through
  // the other phase, i.e. it passed through that state; a phase toggling at its
  // edge (a jiggle) enters and leaves through the same phase and counts nothing.
  if (d == Decoding::Enhanced && delta != 0 && was.last == (a_changed ? 0 : 1)) delta = 0;
  return delta;
}

}  // namespace hsc
}  // namespace plc_cell
