#include "plc_cell/coverage/instruction_text.h"

namespace plc_cell {
namespace coverage {

namespace {

const char* op_text(Op op) {
  switch (op) {
    case Op::Org: return "ORG";
    case Op::OrgNot: return "ORG NOT";
    case Op::OrgUp: return "ORG TU";
    case Op::OrgDown: return "ORG TD";
    case Op::Ld: return "LD";
    case Op::LdNot: return "LD NOT";
    case Op::LdUp: return "LD TU";
    case Op::LdDown: return "LD TD";
    case Op::And: return "AND";
    case Op::AndNot: return "AND NOT";
    case Op::AndUp: return "AND TU";
    case Op::AndDown: return "AND TD";
    case Op::Or: return "OR";
    case Op::OrNot: return "OR NOT";
    case Op::OrUp: return "OR TU";
    case Op::OrDown: return "OR TD";
    case Op::AndLd: return "ANDLD";
    case Op::OrLd: return "ORLD";
    case Op::Out: return "OUT";
    case Op::OutNot: return "OUT NOT";
    case Op::Set: return "SET";
    case Op::Rst:
    case Op::RstReg: return "RST";
    case Op::Tmr: return "TMR";
    case Op::Ctr: return "CTR";
    case Op::Fun: return "FUN";
    case Op::Lbl: return "LBL";
    case Op::Jmp: return "JMP";
    case Op::Call: return "CALL";
    case Op::Rts: return "RTS";
    case Op::Rti: return "RTI";
    case Op::For: return "FOR";
    case Op::Next: return "NEXT";
    case Op::End: return "END";
  }
  return "?";
}

std::string operand_text(const Operand& o) {
  if (!o.text.empty()) return o.text;
  if (o.kind == Operand::Kind::Const) return std::to_string(o.k);
  return format_address(o.addr);
}

}  // namespace

std::string mnemonic(const Instruction& in) {
  if (in.op != Op::Fun) return op_text(in.op);
  return "FUN " + std::to_string(in.fun) + (in.is32 ? "D" : "") + (in.pulse ? "P" : "");
}

std::string instruction_text(const Instruction& in) {
  std::string s = mnemonic(in);
  switch (in.op) {
    case Op::AndLd: case Op::OrLd: case Op::Rts: case Op::Rti: case Op::Next: case Op::End:
      return s;
    case Op::Lbl: case Op::Jmp: case Op::Call:
      return s + " " + in.label;
    case Op::RstReg: case Op::For:
      return in.operands.empty() ? s : s + " " + operand_text(in.operands[0]);
    case Op::Tmr: case Op::Ctr:
      return s + " " + format_address(in.addr) + (in.operands.empty() ? "" : " " + operand_text(in.operands[0]));
    case Op::Fun:
      for (const Operand& o : in.operands)
        if (o.present) s += " " + o.name + "=" + operand_text(o);
      return s;
    default:
      return s + " " + format_address(in.addr);
  }
}

}  // namespace coverage
}  // namespace plc_cell
