#pragma once
// What a FUN refuses among the operands written in the program. The PLC itself only turns
// the instruction's ERR on at run time (and does nothing); since most such operands are
// constants, `plc_cell check` and `plc_cell sim` can say so before the first scan. Each
// FUN declares its rules once, on its FunctionSpec (`rules`, `max_uses`): its handler
// asks the same rules at run time, and operand_warnings() asks them at load.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "plc_cell/core/error.h"
#include "plc_cell/core/program.h"

namespace plc_cell {

struct BoundOperand;
class ExecContext;
class FunctionTable;

// One use of an instruction's operands, in spec order, as far as they are known: at run
// time every value (a register operand is read), at load only the constants written in
// the program. Addresses are known at both times.
class OperandValues {
 public:
  OperandValues(const ExecContext& c, const BoundOperand* ops, size_t n);
  explicit OperandValues(const std::vector<Operand>& ops);

  // The value (0 for an absent operand). At load, reading an operand that is not a
  // constant marks the rule being asked as undecidable.
  int64_t operator[](size_t i) const;
  const Address& address(size_t i) const;
  bool present(size_t i) const;
  // A register operand whose n words (of its area) exist from its address on.
  bool words_fit(size_t i, uint32_t n) const;
  // A discrete output operand whose n bits Y... exist from its address on.
  bool y_fit(size_t i, uint32_t n) const;

  // For the warnings: which operands the last rule read, and whether all were known.
  void begin_rule() const;
  bool rule_decidable() const { return !unknown_; }
  std::string read_operands(const std::vector<std::string>& names) const;  // "Sm=2, Zh=4"

 private:
  const ExecContext* ctx_ = nullptr;
  const BoundOperand* bound_ = nullptr;
  const std::vector<Operand>* parsed_ = nullptr;
  size_t n_ = 0;
  mutable bool unknown_ = false;
  mutable uint64_t read_ = 0;  // bit i: operand i was read by the rule being asked
};

// A rule in the manual's words ("0 <= Sm <= 28, a multiple of 4") and its test.
struct OperandRule {
  std::string text;
  std::function<bool(const OperandValues&)> holds;
};
using OperandRules = std::vector<OperandRule>;

// The first rule the operands break, or null (run time: every rule is decidable).
const OperandRule* broken_rule(const OperandRules& rules, const OperandValues& v);

// At load: a warning at each FUN whose constants break one of its rules, and at each use
// of a FUN beyond its max_uses, with what the PLC will do (its ERR at run time).
std::vector<Diagnostic> operand_warnings(const Program& program, const FunctionTable& functions);

}  // namespace plc_cell
