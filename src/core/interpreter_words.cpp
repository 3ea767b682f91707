// Load-time binding of the word forms (docs/native-engine.md, "FUN calls"): a FUN whose
// operands are all plain registers, constants and flags gets its word form and their
// pointers; a TMR or 16-bit CTR whose preset is a register or a constant gets the preset's
// word.
#include <array>
#include <cstdint>

#include "plc_cell/core/interpreter.h"

namespace plc_cell {

// Where the word forms find operand o of the given role, or null if they cannot: a constant
// outside the width's signed range (ExecContext::get gives it whole), a bit view (WX0), a
// register of the other width, anything but a discrete for a flag.
void* Interpreter::word_pointer(const BoundOperand& o, OperandRole role, bool is32) {
  using Kind = Operand::Kind;
  switch (role) {
    case OperandRole::Source:
      if (o.kind == Kind::Const) {
        const int64_t lo = is32 ? INT32_MIN : INT16_MIN, hi = is32 ? INT32_MAX : INT16_MAX;
        if (o.k < lo || o.k > hi) return nullptr;
        const uint32_t u = static_cast<uint32_t>(o.k);
        constants_.push_back({static_cast<uint16_t>(u), static_cast<uint16_t>(u >> 16)});
        return constants_.back().data();
      }
      [[fallthrough]];
    case OperandRole::Dest:
      return o.kind == (is32 ? Kind::Reg32 : Kind::Reg16) ? o.w : nullptr;
    case OperandRole::BitOut:
      return o.kind == Kind::Bit ? o.b : nullptr;
    default:
      return nullptr;
  }
}

void Interpreter::bind_words(const Instruction& in, Extra* x) {
  if (in.op == Op::Tmr || (in.op == Op::Ctr && x->number < kFirst32BitCounter)) {
    x->preset = static_cast<const uint16_t*>(word_pointer(ops_[x->first_op], OperandRole::Source, false));
    return;
  }
  if (in.op != Op::Fun) return;
  const FunctionSpec& f = *x->fn;
  const WordHandler h = x->is32 ? f.words.w32 : f.words.w16;
  // Word forms see no inputs, no EN and no ExecContext.
  if (!h || f.always_runs || x->n_inputs != 1 || x->n_ops > 6 || x->n_ops > f.operands.size()) return;
  std::array<void*, 6> p{};
  for (uint16_t k = 0; k < x->n_ops; ++k) {
    const OperandSpec& spec = f.operands[k];
    const BoundOperand& o = ops_[x->first_op + k];
    if (spec.span != 1) return;
    if (!o.present) {  // an absent optional flag stays null
      if (spec.role != OperandRole::BitOut) return;
      continue;
    }
    p[k] = word_pointer(o, spec.role, x->is32);
    if (!p[k]) return;
  }
  word_ops_.push_back(p);
  x->words = h;
  x->word_ops = word_ops_.back().data();
}

}  // namespace plc_cell
