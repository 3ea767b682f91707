// An operand of an IL line: a constant, a discrete, a register or a W/DW view.
#include <climits>

#include "il_parse.h"
#include "plc_cell/core/address.h"
#include "plc_cell/core/il_parser.h"

namespace plc_cell {
namespace il {

bool Parser::bit_address(const Token& t, Address* a) {
  std::string why;
  if (!try_parse_address(t.text, a, &why)) {
    error(t.column, "bad address " + why);
    return false;
  }
  if (a->width != Width::Bit) {
    error(t.column, "'" + t.text + "' is a register; this instruction needs a discrete such as X0, Y0 or M0");
    return false;
  }
  return true;
}

bool Parser::value_operand(const Token& t, bool is32, OperandRole role, uint8_t span, Operand* o) {
  int64_t k;
  o->column = t.column;
  if (role == OperandRole::Label) {  // a name; the function checks it when it runs
    o->kind = Operand::Kind::Const;
    o->text = upper(t.text);
    return true;
  }
  if (parse_constant(t.text, &k)) return constant_operand(t, is32, role, k, o);
  if (misspelt_constant(t, role)) return false;
  Address a;
  std::string why;
  if (!try_parse_address(t.text, &a, &why)) {
    error(t.column, "bad operand " + why);
    return false;
  }
  o->addr = a;
  if (role == OperandRole::BitOut || role == OperandRole::BitIn) {
    if (a.width != Width::Bit) {
      error(t.column, "'" + t.text + "' must be a discrete such as M0");
      return false;
    }
    if (role == OperandRole::BitOut && a.area == Area::X) {
      error(t.column, "'" + t.text + "' is an input and cannot be written");
      return false;
    }
    o->kind = Operand::Kind::Bit;
    return true;
  }
  if (a.width == Width::Bit) {
    error(t.column, "'" + t.text + "' is a single discrete; use a register or a W/DW view such as WM0");
    return false;
  }
  if (role == OperandRole::Register && is_discrete(a.area)) {
    error(t.column, "'" + t.text + "' must be a register (R, D, F, RT, RC)");
    return false;
  }
  return register_operand(t, a, is32, span, o);
}

bool Parser::constant_operand(const Token& t, bool is32, OperandRole role, int64_t k, Operand* o) {
  if (role != OperandRole::Source && role != OperandRole::Const) {
    error(t.column, "'" + t.text + "' is a constant; this operand must be an address");
    return false;
  }
  const int64_t lo = is32 ? INT32_MIN : -32768, hi = is32 ? int64_t(UINT32_MAX) : 65535;
  if (k < lo || k > hi) {
    error(t.column, "constant " + t.text + " does not fit in " + (is32 ? "32" : "16") +
                        " bits" + (is32 ? "" : " (use the .D form)"));
    return false;
  }
  o->kind = Operand::Kind::Const;
  o->k = k;
  return true;
}

// A constant written the wrong way, or an address where only a constant may stand:
// reported, true.
bool Parser::misspelt_constant(const Token& t, OperandRole role) {
  const std::string u = upper(t.text);
  if (u.size() > 2 && (u[0] == '-' || u[0] == '+') && u[1] == 'K') {
    error(t.column, "'" + t.text + "': the sign goes after K (K" + u.substr(0, 1) + u.substr(2) + ")");
    return true;
  }
  if (u.size() > 2 && u[0] == 'H' && (u[1] == '-' || u[1] == '+')) {
    error(t.column, "'" + t.text + "': a hexadecimal constant has no sign; write the two's complement (H-1 is HFFFF)");
    return true;
  }
  if (role == OperandRole::Const) {
    error(t.column, "'" + t.text + "' must be a constant");
    return true;
  }
  return false;
}

// A register or a W/DW view of discretes: its width against the instruction's, and the
// registers it spans.
bool Parser::register_operand(const Token& t, const Address& a, bool is32, uint8_t span, Operand* o) {
  if (a.width == Width::DWord && !is32) {
    error(t.column, "'" + t.text + "' is 32-bit; use the .D form of the instruction");
    return false;
  }
  const bool wide = is32 || a.width == Width::DWord;
  Address span_start = a;
  uint32_t count = span;
  if (is_discrete(a.area)) {
    span_start.width = wide ? Width::DWord : Width::Word;
    o->kind = wide ? Operand::Kind::Bits32 : Operand::Kind::Bits16;
  } else {
    o->kind = wide ? Operand::Kind::Reg32 : Operand::Kind::Reg16;
    span_start.width = wide ? Width::DWord : Width::Word;
    if (a.area == Area::RC && a.index >= kFirst32BitCounter && !wide) {
      error(t.column, "'" + t.text + "' is a 32-bit counter; use the .D form");
      return false;
    }
  }
  try {
    check_span(span_start, count);
  } catch (const Error& e) {
    error(t.column, e.what());
    return false;
  }
  return true;
}

}  // namespace il
}  // namespace plc_cell
