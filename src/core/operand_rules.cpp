#include "plc_cell/core/operand_rules.h"

#include <map>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/memory.h"

namespace plc_cell {

OperandValues::OperandValues(const ExecContext& c, const BoundOperand* ops, size_t n) : ctx_(&c), bound_(ops), n_(n) {}

OperandValues::OperandValues(const std::vector<Operand>& ops) : parsed_(&ops), n_(ops.size()) {}

int64_t OperandValues::operator[](size_t i) const {
  if (i >= n_) return 0;
  if (i < 64) read_ |= uint64_t(1) << i;
  if (bound_) return bound_[i].present ? ctx_->get(bound_[i]) : 0;
  const Operand& o = (*parsed_)[i];
  if (!o.present) return 0;
  if (o.kind != Operand::Kind::Const) unknown_ = true;  // a register's value comes at run time
  return o.kind == Operand::Kind::Const ? o.k : 0;
}

const Address& OperandValues::address(size_t i) const {
  static const Address none{};
  if (i >= n_) return none;
  return bound_ ? bound_[i].addr : (*parsed_)[i].addr;
}

bool OperandValues::present(size_t i) const {
  if (i >= n_) return false;
  return bound_ ? bound_[i].present : (*parsed_)[i].present;
}

bool OperandValues::words_fit(size_t i, uint32_t n) const {
  if (!present(i)) return false;
  const bool reg = bound_ ? bound_[i].w != nullptr
                          : (*parsed_)[i].kind == Operand::Kind::Reg16 || (*parsed_)[i].kind == Operand::Kind::Reg32;
  const Address& a = address(i);
  return reg && a.index + uint64_t(n) <= Memory::word_count(a.area);
}

bool OperandValues::y_fit(size_t i, uint32_t n) const {
  const Address& a = address(i);
  return present(i) && a.area == Area::Y && a.index + uint64_t(n) <= 256;
}

void OperandValues::begin_rule() const {
  unknown_ = false;
  read_ = 0;
}

std::string OperandValues::read_operands(const std::vector<std::string>& names) const {
  std::string s;
  for (size_t i = 0; i < n_ && i < 64 && i < names.size(); ++i)
    if (read_ >> i & 1u) s += (s.empty() ? "" : " ") + names[i] + "=" + std::to_string((*this)[i]);
  return s;
}

const OperandRule* broken_rule(const OperandRules& rules, const OperandValues& v) {
  for (const OperandRule& r : rules) {
    v.begin_rule();
    if (!r.holds(v) && v.rule_decidable()) return &r;
  }
  return nullptr;
}

std::vector<Diagnostic> operand_warnings(const Program& program, const FunctionTable& functions) {
  std::vector<Diagnostic> out;
  std::map<uint16_t, std::vector<int>> uses;  // FUN number -> the lines of its uses so far
  const auto warn = [&](const Instruction& ins, const std::string& message) {
    Diagnostic d;
    d.where = {program.file, ins.line, ins.column};
    d.message = message;
    d.warning = true;
    out.push_back(d);
  };
  for (const Instruction& ins : program.code) {
    if (ins.op != Op::Fun) continue;
    const FunctionSpec* spec = functions.find(ins.fun);
    if (!spec) continue;
    const std::string fun = "FUN " + std::to_string(spec->number) + " " + spec->mnemonic;
    const std::string consequence = ": at run time the PLC turns its ERR on and the instruction does nothing";
    auto& lines = uses[spec->number];
    if (spec->max_uses && lines.size() >= spec->max_uses)
      warn(ins, fun + ": may be used " + (spec->max_uses == 1 ? "once" : std::to_string(spec->max_uses) + " times") +
                    " in a program, this is use " + std::to_string(lines.size() + 1) + " (the first at line " +
                    std::to_string(lines.front()) + ")" + consequence);
    lines.push_back(ins.line);
    if (spec->rules.empty()) continue;
    std::vector<std::string> names;
    for (const OperandSpec& o : spec->operands) names.push_back(o.name);
    const OperandValues v(ins.operands);
    for (const OperandRule& r : spec->rules) {
      v.begin_rule();
      if (r.holds(v) || !v.rule_decidable()) continue;
      const std::string given = v.read_operands(names);
      warn(ins, fun + ": " + (given.empty() ? "" : given + ": ") + "needs " + r.text + consequence);
    }
  }
  return out;
}

}  // namespace plc_cell
