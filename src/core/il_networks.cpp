// The network of a rung: contacts and LD blocks, the outputs that close it, TMR and CTR.
#include "il_parse.h"
#include "plc_cell/core/interpreter.h"

namespace plc_cell {
namespace il {

bool Parser::need_network(const Token& t) {
  if (!network_open_) {
    error(t.column, t.text + " has no input: start the network with ORG");
    return false;
  }
  return true;
}

bool Parser::output_ok(const Token& t, int inputs) {
  if (!need_network(t)) return false;
  if (depth_ != inputs - 1) {
    if (inputs == 1)
      error(t.column, std::to_string(depth_) + " LD block(s) still open before " + t.text +
                          ": close them with ANDLD or ORLD");
    else
      error(t.column, t.text + " takes " + std::to_string(inputs) + " inputs (ORG then " +
                          std::to_string(inputs - 1) + " LD), but " + std::to_string(depth_ + 1) +
                          " are on the stack");
    return false;
  }
  depth_ = 0;
  return true;
}

void Parser::contact(const std::string& m, const std::vector<Token>& toks) {
  const Token& head = toks[0];
  size_t k = 1;
  std::string mod;
  if (k < toks.size()) {
    const std::string u = upper(toks[k].text);
    if (u == "NOT" || u == "TU" || u == "TD") {
      mod = u;
      ++k;
    }
  }
  if (k >= toks.size()) return error(head.column, m + " needs a discrete operand, e.g. " + m + " X0");
  if (k + 1 < toks.size()) error(toks[k + 1].column, "unexpected '" + toks[k + 1].text + "'");
  Address a;
  if (!bit_address(toks[k], &a)) return;
  const int kind = m == "ORG" ? 0 : m == "LD" ? 1 : m == "AND" ? 2 : 3;
  if (kind >= 1 && !need_network(head)) return;
  if (kind == 1 && depth_ == Interpreter::kMaxStack - 1)
    return error(head.column, "too many nested LD blocks");
  static const Op plain[] = {Op::Org, Op::Ld, Op::And, Op::Or};
  static const Op negated[] = {Op::OrgNot, Op::LdNot, Op::AndNot, Op::OrNot};
  static const Op up[] = {Op::OrgUp, Op::LdUp, Op::AndUp, Op::OrUp};
  static const Op down[] = {Op::OrgDown, Op::LdDown, Op::AndDown, Op::OrDown};
  const Op op = mod.empty() ? plain[kind] : mod == "NOT" ? negated[kind] : mod == "TU" ? up[kind] : down[kind];
  Instruction& in = emit(op, head);
  in.addr = a;
  if (mod == "TU" || mod == "TD") new_edge_slot();
  if (kind == 0) {
    network_open_ = true;
    depth_ = 0;
  }
  if (kind == 1) ++depth_;
}

void Parser::out(const std::vector<Token>& toks) {
  const Token& head = toks[0];
  size_t k = 1;
  bool neg = false;
  if (k < toks.size() && upper(toks[k].text) == "NOT") {
    neg = true;
    ++k;
  }
  if (k >= toks.size()) return error(head.column, "OUT needs a discrete operand, e.g. OUT Y0");
  if (k + 1 < toks.size()) error(toks[k + 1].column, "unexpected '" + toks[k + 1].text + "'");
  Address a;
  if (!bit_address(toks[k], &a)) return;
  if (a.area == Area::X) return error(toks[k].column, "OUT cannot drive an input (" + toks[k].text + ")");
  if (a.area == Area::T || a.area == Area::C)
    return error(toks[k].column, "timer and counter contacts are driven by TMR/CTR, not OUT");
  if (!output_ok(head, 1)) return;
  emit(neg ? Op::OutNot : Op::Out, head).addr = a;
}

void Parser::set_rst(const std::string& m, const std::vector<Token>& toks) {
  const Token& head = toks[0];
  if (toks.size() < 2) return error(head.column, m + " needs an operand, e.g. " + m + " Y0");
  if (toks.size() > 2) error(toks[2].column, "unexpected '" + toks[2].text + "'");
  Address a;
  std::string why;
  if (!try_parse_address(toks[1].text, &a, &why)) return error(toks[1].column, "bad address " + why);
  if (!output_ok(head, 1)) return;
  if (a.width == Width::Bit) {
    if (a.area == Area::X) return error(toks[1].column, m + " cannot drive an input");
    if (m == "SET" && (a.area == Area::T || a.area == Area::C))
      return error(toks[1].column, "SET cannot drive a timer or counter contact");
    emit(m == "SET" ? Op::Set : Op::Rst, head).addr = a;
    return;
  }
  if (m == "SET") return error(toks[1].column, "SET needs a discrete; use MOV to set a register");
  if (is_discrete(a.area)) return error(toks[1].column, "RST of a W/DW view is not supported; use MOV 0");
  Instruction& in = emit(Op::RstReg, head);
  in.is32 = a.width == Width::DWord;
  Operand o;
  o.kind = in.is32 ? Operand::Kind::Reg32 : Operand::Kind::Reg16;
  o.addr = a;
  in.operands.push_back(o);
}

void Parser::timer_counter(const std::string& m, const std::vector<Token>& toks) {
  const Token& head = toks[0];
  if (toks.size() != 3)
    return error(head.column, m + " takes a " + (m == "TMR" ? "timer and a preset, e.g. TMR T0 100"
                                                            : "counter and a preset, e.g. CTR C0 10"));
  Address a;
  if (!bit_address(toks[1], &a)) return;
  const Area want = m == "TMR" ? Area::T : Area::C;
  if (a.area != want) return error(toks[1].column, m + " needs " + (m == "TMR" ? "a timer T0..T255" : "a counter C0..C255"));
  const bool wide = m == "CTR" && a.index >= kFirst32BitCounter;
  Address pa;
  std::string ignored;
  if (!wide && try_parse_address(toks[2].text, &pa, &ignored) && pa.width == Width::DWord)
    return error(toks[2].column, "'" + toks[2].text + "' is 32-bit; " + toks[1].text +
                                     " takes a 16-bit preset (only C200-C255 take a 32-bit one)");
  Operand pv;
  if (!value_operand(toks[2], wide, OperandRole::Source, 1, &pv)) return;
  if (pv.kind == Operand::Kind::Const && (pv.k < 0 || pv.k > (wide ? INT32_MAX : 32767)))
    return error(toks[2].column, "preset " + toks[2].text + " out of range (0.." +
                                     (wide ? std::string("2147483647") : std::string("32767")) + ")");
  if (!output_ok(head, 1)) return;
  Instruction& in = emit(m == "TMR" ? Op::Tmr : Op::Ctr, head);
  in.addr = a;
  in.is32 = wide;
  in.operands.push_back(pv);
  if (m == "CTR") new_edge_slot();
}

}  // namespace il
}  // namespace plc_cell
