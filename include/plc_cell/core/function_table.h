#pragma once
// The FUN instruction registry. The core registers move, arithmetic, compare,
// logic, shift and code conversion; later subsystems (motion, counters, PID,
// communication) register theirs the same way.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "plc_cell/core/operand_rules.h"
#include "plc_cell/core/program.h"

namespace plc_cell {

class Memory;
class ExecContext;

enum class OperandRole : uint8_t {
  Source,   // constant or register (W/DW views allowed)
  Dest,     // register or W/DW view
  BitOut,   // a discrete output (flags such as EQ, CY, ERR)
  BitIn,    // a discrete read
  Const,    // a constant only
  Register, // a register base address (tables, working areas); no constant
  Label,    // a name such as an interrupt label (FUN145 EN X0+I); kept as upper-case text
};

struct OperandSpec {
  std::string name;
  OperandRole role;
  bool optional = false;
  uint8_t span = 1;  // elements of the instruction's width it covers (MUL's D holds 2)
};

// Bound operand: resolved pointers into one Memory.
struct BoundOperand {
  Operand::Kind kind = Operand::Kind::Const;
  int64_t k = 0;
  uint16_t* w = nullptr;
  uint8_t* b = nullptr;
  Address addr{};
  bool present = false;
  std::string text;  // OperandRole::Label: the name as written, upper case
};

using FunctionHandler = std::function<void(ExecContext&, const BoundOperand* ops)>;

// A FUN's word form (docs/native-engine.md, "FUN calls"): its handler compiled for operands
// that are all bound pointers, each a register's word (a constant: a slot of two words), a
// discrete's byte (a flag) or null (an absent optional flag), passed in order (o0 is the
// first operand). Where an instruction's operands allow it, both engines call this form
// instead of `handler`, without an ExecContext. It comes from the same body as `handler`
// (core/fun_forms.h), so the two cannot differ; it never throws.
using WordHandler = void (*)(void* o0, void* o1, void* o2, void* o3, void* o4, void* o5) noexcept;
struct WordForms {
  WordHandler w16 = nullptr;  // 16-bit: every operand a Reg16 or a constant in int16 range
  WordHandler w32 = nullptr;  // .D: every operand a Reg32 or a constant in int32 range
};

struct FunctionSpec {
  uint16_t number = 0;
  std::string mnemonic;
  std::vector<std::string> inputs{"EN"};  // first is EN; more come from the LD stack
  std::vector<OperandSpec> operands;
  bool allow_32 = true;
  bool allow_pulse = true;
  bool always_runs = false;  // called with EN off too (instructions that track their input)
  FunctionHandler handler;
  // Optional word forms of handler, for one-input FUNs of up to six operands that read and
  // write only Source/Dest values and BitOut flags, and never throw.
  WordForms words;
  // Optional parse-time check of the operands (in spec order); a non-empty answer
  // is reported as an error at the instruction.
  std::function<std::string(const std::vector<Operand>&)> check;
  // What the PLC accepts in the program but refuses at run time with ERR (operand ranges,
  // tables that must fit): the handler asks these rules each execution, and `check` and
  // `sim` ask them at load, warning where the constants already break one
  // (core/operand_rules.h).
  OperandRules rules;
  // How many times a program may use the instruction (0: any); a use beyond is warned.
  uint16_t max_uses = 0;
};

class FunctionTable {
 public:
  // A table with the core's functions. A cell's whole instruction set adds each
  // subsystem's (SoftCell::functions()): the core knows none of them.
  static FunctionTable with_core_functions();

  void add(FunctionSpec spec);  // throws if the number or mnemonic is taken
  const FunctionSpec* find(uint16_t number) const;
  const FunctionSpec* find(const std::string& mnemonic) const;  // case-insensitive
  const std::vector<FunctionSpec>& all() const { return specs_; }

  // A FUN this table does not offer, with the reason the parser reports at its line
  // (e.g. an instruction of another PLC generation). Found by number or mnemonic.
  void add_unavailable(uint16_t number, const std::string& mnemonic, const std::string& why);
  // "FUN 72 TP4: <why>", or empty if the number/mnemonic is simply unknown.
  std::string why_unavailable(uint16_t number) const;
  std::string why_unavailable(const std::string& mnemonic) const;

 private:
  struct Unavailable {
    uint16_t number;
    std::string mnemonic, why;
  };
  std::vector<Unavailable> unavailable_;
  std::vector<FunctionSpec> specs_;
  std::vector<int> by_number_ = std::vector<int>(1024, -1);
};

}  // namespace plc_cell
