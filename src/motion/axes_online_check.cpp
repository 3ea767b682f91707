#include "plc_cell/motion/axes_online_check.h"

#include "plc_cell/motion/motion_unit.h"

namespace plc_cell {
namespace motion {

namespace {

using IlOperand = plc_cell::Operand;

const IlOperand* operand(const Instruction& in, const char* name) {
  for (const auto& o : in.operands)
    if (o.name == name && o.present) return &o;
  return nullptr;
}

// The FUN140 of axis ps in p, or nullptr.
const Instruction* fun140_of(const plc_cell::Program& p, int ps) {
  for (const auto& in : p.code) {
    if (in.op != Op::Fun || in.fun != 140) continue;
    const IlOperand* axis = operand(in, "Ps");
    if (axis && axis->kind == IlOperand::Kind::Const && axis->k == ps) return &in;
  }
  return nullptr;
}

bool same_table(const Instruction& a, const Instruction& b) {
  const IlOperand *x = operand(a, "SR"), *y = operand(b, "SR");
  if (!x || !y) return x == y;
  return x->kind == y->kind && x->k == y->k && x->addr.area == y->addr.area && x->addr.index == y->addr.index;
}

}  // namespace

std::vector<std::string> AxesOnlineCheck::refusals(const plc_cell::Program& running, const plc_cell::Program& next) const {
  std::vector<std::string> out;
  for (int ps = 0; ps < kAxes; ++ps) {
    if (!unit_->program_running(ps)) continue;
    const Instruction* now = fun140_of(running, ps);
    const Instruction* then = fun140_of(next, ps);
    if (now && then && same_table(*now, *then)) continue;
    const std::string where = now ? " (FUN140 at " + running.file + ":" + std::to_string(now->line) + ")" : "";
    out.push_back("axis " + std::to_string(ps) + " is running its FUN140 table" + where +
                  (then ? " and the new program points its FUN140 at another table"
                        : " and the new program has no FUN140 for it") +
                  ": stop the axis (ABT) first");
  }
  return out;
}

}  // namespace motion
}  // namespace plc_cell
