#include "plc_cell/coverage/same_program.h"

#include "plc_cell/coverage/instruction_text.h"

namespace plc_cell {
namespace coverage {

namespace {

bool same(const Operand& a, const Operand& b) {
  return a.kind == b.kind && a.k == b.k && a.addr == b.addr && a.name == b.name && a.present == b.present &&
         a.text == b.text;
}

bool same(const Instruction& a, const Instruction& b) {
  if (a.op != b.op || a.is32 != b.is32 || a.pulse != b.pulse || a.fun != b.fun || a.addr != b.addr ||
      a.target != b.target || a.label != b.label || a.line != b.line || a.column != b.column ||
      a.operands.size() != b.operands.size())
    return false;
  for (size_t i = 0; i < a.operands.size(); ++i)
    if (!same(a.operands[i], b.operands[i])) return false;
  return true;
}

}  // namespace

std::string program_difference(const Program& a, const Program& b) {
  if (a.file != b.file) return "it is another file";
  if (a.code.size() != b.code.size())
    return std::to_string(b.code.size()) + " instructions, not " + std::to_string(a.code.size());
  for (size_t i = 0; i < a.code.size(); ++i)
    if (!same(a.code[i], b.code[i]))
      return "instruction " + std::to_string(i + 1) + " is " + instruction_text(b.code[i]) + " on line " +
             std::to_string(b.code[i].line) + ", not " + instruction_text(a.code[i]) + " on line " +
             std::to_string(a.code[i].line);
  if (a.main_end != b.main_end || a.labels != b.labels) return "its labels differ";
  return "";
}

}  // namespace coverage
}  // namespace plc_cell
