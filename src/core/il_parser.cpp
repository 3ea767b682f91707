#include "plc_cell/core/il_parser.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <sstream>

#include "plc_cell/core/error.h"
#include "plc_cell/core/interpreter.h"
// The reserved interrupt labels: they cannot be jump targets.
#include "plc_cell/core/interrupt_sources.h"
#include "plc_cell/core/unreadable.h"

namespace plc_cell {
namespace {

struct Token {
  std::string text;
  int column;
};

std::string upper(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::vector<Token> tokenize(const std::string& line) {
  std::vector<Token> out;
  size_t end = line.size();
  for (size_t i = 0; i < line.size(); ++i) {
    if (line[i] == ';' || (line[i] == '/' && i + 1 < line.size() && line[i + 1] == '/')) {
      end = i;
      break;
    }
  }
  size_t i = 0;
  while (i < end) {
    while (i < end && (std::isspace(static_cast<unsigned char>(line[i])) || line[i] == ',')) ++i;
    if (i >= end) break;
    size_t j = i;
    while (j < end && !std::isspace(static_cast<unsigned char>(line[j])) && line[j] != ',') ++j;
    out.push_back({line.substr(i, j - i), static_cast<int>(i) + 1});
    i = j;
  }
  return out;
}

struct FlowFun {
  uint16_t number;
  const char* name;
};
const FlowFun kFlowFuns[] = {{65, "LBL"}, {66, "JMP"}, {67, "CALL"}, {68, "RTS"},
                             {69, "RTI"}, {70, "FOR"}, {71, "NEXT"}};

class Parser {
 public:
  Parser(const std::string& file, const FunctionTable& fns) : fns_(fns) { prog_.file = file; }

  Program run(std::string_view text) {
    std::istringstream in{std::string(text)};
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
      ++n;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      line_ = n;
      auto toks = tokenize(line);
      if (!toks.empty()) statement(toks);
    }
    finish();
    if (!errors_.empty()) throw SourceError(errors_);
    return std::move(prog_);
  }

 private:
  void error(int column, const std::string& msg) {
    errors_.push_back({{prog_.file, line_, column}, msg});
  }

  Instruction& emit(Op op, const Token& at) {
    Instruction in;
    in.op = op;
    in.line = line_;
    in.column = at.column;
    prog_.code.push_back(std::move(in));
    return prog_.code.back();
  }

  void new_edge_slot() {
    prog_.edge_slot_of.resize(prog_.code.size(), ~0u);
    prog_.edge_slot_of.back() = prog_.edge_slots++;
  }

  bool bit_address(const Token& t, Address* a) {
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

  bool need_network(const Token& t) {
    if (!network_open_) {
      error(t.column, t.text + " has no input: start the network with ORG");
      return false;
    }
    return true;
  }

  // Output instructions consume the network's open LD blocks down to inputs-1.
  bool output_ok(const Token& t, int inputs) {
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

  void statement(const std::vector<Token>& toks) {
    const Token& head = toks[0];
    const std::string m = upper(head.text);
    if (m == "END") return end(toks);
    if (after_end_ && !in_routine_ && m != "LBL") {
      error(head.column, "code after END must belong to a subroutine or interrupt routine: start it with LBL");
      return;
    }
    if (m == "ORG" || m == "LD" || m == "AND" || m == "OR") return contact(m, toks);
    if (m == "ANDLD" || m == "ORLD") {
      if (!need_network(head)) return;
      if (toks.size() > 1) error(toks[1].column, m + " takes no operand");
      if (depth_ == 0) return error(head.column, m + " without a matching LD");
      --depth_;
      emit(m == "ANDLD" ? Op::AndLd : Op::OrLd, head);
      return;
    }
    if (m == "OUT") return out(toks);
    if (m == "SET" || m == "RST") return set_rst(m, toks);
    if (m == "TMR" || m == "CTR") return timer_counter(m, toks);
    if (m == "FUN") return fun_numbered(toks);
    for (const auto& f : kFlowFuns)
      if (m == f.name) return flow(m, toks, 1);
    // A function mnemonic, optionally with .D / .P / .DP.
    std::string base = m, mods;
    const auto dot = m.find('.');
    if (dot != std::string::npos) {
      base = m.substr(0, dot);
      mods = m.substr(dot + 1);
    }
    if (const FunctionSpec* spec = fns_.find(base)) return fun(spec, mods, head, toks, 1);
    const std::string why = fns_.why_unavailable(base);
    error(head.column, why.empty() ? "unknown instruction '" + head.text + "'" : why);
  }

  void contact(const std::string& m, const std::vector<Token>& toks) {
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

  void out(const std::vector<Token>& toks) {
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

  void set_rst(const std::string& m, const std::vector<Token>& toks) {
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

  bool value_operand(const Token& t, bool is32, OperandRole role, uint8_t span, Operand* o) {
    int64_t k;
    if (role == OperandRole::Label) {  // a name; the function checks it when it runs
      o->kind = Operand::Kind::Const;
      o->text = upper(t.text);
      return true;
    }
    if (parse_constant(t.text, &k)) {
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
    const std::string u = upper(t.text);
    if (u.size() > 2 && (u[0] == '-' || u[0] == '+') && u[1] == 'K') {
      error(t.column, "'" + t.text + "': the sign goes after K (K" + u.substr(0, 1) + u.substr(2) + ")");
      return false;
    }
    if (u.size() > 2 && u[0] == 'H' && (u[1] == '-' || u[1] == '+')) {
      error(t.column, "'" + t.text + "': a hexadecimal constant has no sign; write the two's complement (H-1 is HFFFF)");
      return false;
    }
    if (role == OperandRole::Const) {
      error(t.column, "'" + t.text + "' must be a constant");
      return false;
    }
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

  void timer_counter(const std::string& m, const std::vector<Token>& toks) {
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

  void end(const std::vector<Token>& toks) {
    if (toks.size() > 1) error(toks[1].column, "END takes no operand");
    if (after_end_) return error(toks[0].column, "second END: the main program already ended on line " +
                                                     std::to_string(end_line_));
    check_open_fors(toks[0]);
    after_end_ = true;
    end_line_ = line_;
    network_open_ = false;
    prog_.main_end = static_cast<uint32_t>(prog_.code.size());
    emit(Op::End, toks[0]);
  }

  void check_open_fors(const Token& at) {
    for (size_t i = 0; i < fors_.size(); ++i)
      error(at.column, "FOR on line " + std::to_string(prog_.code[fors_[i]].line) + " has no NEXT");
    fors_.clear();
  }

  void flow(const std::string& m, const std::vector<Token>& toks, size_t first) {
    const Token& head = toks[0];
    auto operand = [&](const char* what) -> const Token* {
      if (first >= toks.size()) {
        error(head.column, m + " needs " + what);
        return nullptr;
      }
      if (first + 1 < toks.size()) error(toks[first + 1].column, "unexpected '" + toks[first + 1].text + "'");
      return &toks[first];
    };
    if (m == "LBL") {
      const Token* t = operand("a label name");
      if (!t) return;
      const std::string name = upper(t->text);
      if (!after_end_ && irq::source_of_label(name) >= 0)
        return error(t->column, name + " is an interrupt label: its routine belongs after END (LBL " + name +
                                    " ... RTI)");
      if (prog_.labels.count(name))
        return error(t->column, "label " + t->text + " is defined twice (first on line " +
                                    std::to_string(prog_.code[prog_.labels[name]].line) + ")");
      // Inside an open FOR body a label is a jump target within that body, in a routine as
      // in the main program; FOR and NEXT pair by position, and one left open is reported
      // at END or, after END, at the end of the file.
      if (after_end_) in_routine_ = true;
      prog_.labels[name] = static_cast<uint32_t>(prog_.code.size());
      label_region_[name] = after_end_;
      emit(Op::Lbl, head).label = name;
      network_open_ = false;
      return;
    }
    if (m == "JMP" || m == "CALL") {
      const Token* t = operand("a label name");
      if (!t) return;
      if (!output_ok(head, 1)) return;
      // An interrupt routine runs on its interrupt and returns with RTI: never a jump target.
      if (irq::source_of_label(upper(t->text)) >= 0)
        return error(t->column, m + " " + upper(t->text) + ": " + upper(t->text) +
                                    " is an interrupt label; its routine runs on the interrupt, not by " + m);
      Instruction& in = emit(m == "JMP" ? Op::Jmp : Op::Call, head);
      in.label = upper(t->text);
      refs_.push_back({prog_.code.size() - 1, t->column, after_end_});
      return;
    }
    if (m == "RTS" || m == "RTI") {
      if (first < toks.size()) error(toks[first].column, m + " takes no operand");
      if (!after_end_) return error(head.column, m + " belongs in the subroutine area after END");
      emit(m == "RTS" ? Op::Rts : Op::Rti, head);
      network_open_ = false;
      return;
    }
    if (m == "FOR") {
      const Token* t = operand("a loop count, e.g. FOR 10 or FOR R2");
      if (!t) return;
      Operand o;
      if (!value_operand(*t, false, OperandRole::Source, 1, &o)) return;
      if (fors_.size() == 5) return error(head.column, "FOR nested deeper than 5");
      fors_.push_back(static_cast<uint32_t>(prog_.code.size()));
      emit(Op::For, head).operands.push_back(o);
      network_open_ = false;
      return;
    }
    if (m == "NEXT") {
      if (first < toks.size()) error(toks[first].column, "NEXT takes no operand");
      if (fors_.empty()) return error(head.column, "NEXT without FOR");
      prog_.code[fors_.back()].target = static_cast<uint32_t>(prog_.code.size());
      fors_.pop_back();
      emit(Op::Next, head);
      network_open_ = false;
      return;
    }
  }

  void fun_numbered(const std::vector<Token>& toks) {
    const Token& head = toks[0];
    if (toks.size() < 2) return error(head.column, "FUN needs a function number, e.g. FUN 8 S=R0 D=R1");
    const std::string t = upper(toks[1].text);
    size_t i = 0;
    while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) ++i;
    if (i == 0 || i > 4) return error(toks[1].column, "'" + toks[1].text + "' is not a function number");
    const uint16_t number = static_cast<uint16_t>(std::stoi(t.substr(0, i)));
    std::string mods = t.substr(i);
    if (!mods.empty() && mods[0] == '.') mods.erase(0, 1);
    for (const auto& f : kFlowFuns)
      if (f.number == number) return flow(f.name, toks, 2);
    const FunctionSpec* spec = fns_.find(number);
    if (!spec) {
      const std::string why = fns_.why_unavailable(number);
      return error(toks[1].column, why.empty() ? "FUN " + std::to_string(number) + " is not available in plc_cell" : why);
    }
    size_t first = 2;
    if (first < toks.size() && toks[first].text.find('=') == std::string::npos) {
      // The mnemonic may follow the number, with the modifiers on either (FUN 8D MOV, FUN 8 MOV.D).
      const std::string word = upper(toks[first].text);
      const auto dot = word.find('.');
      const std::string base = word.substr(0, dot);
      const std::string more = dot == std::string::npos ? "" : word.substr(dot + 1);
      if (base == upper(spec->mnemonic)) {
        if (!more.empty() && !mods.empty())
          return error(toks[first].column, "modifiers given twice ('" + toks[1].text + "' and '" +
                                               toks[first].text + "'): write them on one of the two");
        mods += more;
        ++first;
      } else if (const FunctionSpec* other = fns_.find(base)) {
        if (other->number != spec->number)
          return error(toks[first].column, "FUN " + std::to_string(spec->number) + " is " + spec->mnemonic + "; " +
                                               base + " is FUN " + std::to_string(other->number));
      }
    }
    fun(spec, mods, toks[1], toks, first);
  }

  void fun(const FunctionSpec* spec, const std::string& mods, const Token& at,
           const std::vector<Token>& toks, size_t first) {
    bool is32 = false, pulse = false;
    for (char c : mods) {
      if (c == 'D' && !is32) is32 = true;
      else if (c == 'P' && !pulse) pulse = true;
      else return error(at.column, "unknown modifier '" + mods + "' (use D for 32-bit, P for pulse)");
    }
    const std::string name = "FUN" + std::to_string(spec->number) + " " + spec->mnemonic;
    if (is32 && !spec->allow_32) return error(at.column, name + " has no 32-bit (D) form");
    if (pulse && !spec->allow_pulse) return error(at.column, name + " has no pulse (P) form");
    std::vector<Operand> ops(spec->operands.size());
    std::vector<bool> given(spec->operands.size(), false);
    size_t next_positional = 0;
    bool ok = true;
    for (size_t k = first; k < toks.size(); ++k) {
      const Token& t = toks[k];
      size_t slot;
      Token value = t;
      const auto eq = t.text.find('=');
      if (eq != std::string::npos) {
        const std::string key = upper(t.text.substr(0, eq));
        slot = spec->operands.size();
        for (size_t s = 0; s < spec->operands.size(); ++s)
          if (upper(spec->operands[s].name) == key) slot = s;
        if (slot == spec->operands.size()) {
          std::string names;
          for (const auto& o : spec->operands) names += (names.empty() ? "" : ", ") + o.name;
          error(t.column, name + " has no operand '" + t.text.substr(0, eq) + "' (operands: " + names + ")");
          ok = false;
          continue;
        }
        value.text = t.text.substr(eq + 1);
        value.column = t.column + static_cast<int>(eq) + 1;
      } else {
        while (next_positional < given.size() && given[next_positional]) ++next_positional;
        if (next_positional >= spec->operands.size()) {
          error(t.column, name + " takes " + std::to_string(spec->operands.size()) + " operand(s); '" +
                              t.text + "' is one too many");
          ok = false;
          continue;
        }
        slot = next_positional;
      }
      if (given[slot]) {
        error(t.column, "operand " + spec->operands[slot].name + " given twice");
        ok = false;
        continue;
      }
      given[slot] = true;
      ops[slot].name = spec->operands[slot].name;
      if (!value_operand(value, is32, spec->operands[slot].role, spec->operands[slot].span, &ops[slot])) ok = false;
    }
    for (size_t s = 0; s < spec->operands.size(); ++s) {
      ops[s].name = spec->operands[s].name;
      if (given[s]) continue;
      if (spec->operands[s].optional) {
        ops[s].present = false;
        continue;
      }
      error(at.column, name + " needs operand " + spec->operands[s].name);
      ok = false;
    }
    if (!ok) return;
    if (spec->check) {
      const std::string why = spec->check(ops);
      if (!why.empty()) return error(at.column, name + ": " + why);
    }
    if (!output_ok(toks[0], static_cast<int>(spec->inputs.size()))) return;
    Instruction& in = emit(Op::Fun, toks[0]);
    in.fun = spec->number;
    in.is32 = is32;
    in.pulse = pulse;
    in.operands = std::move(ops);
    if (pulse) new_edge_slot();
  }

  void finish() {
    const Token eof{"", 0};
    if (!after_end_) {
      Diagnostic d;
      d.where.file = prog_.file;
      d.where.line = line_;
      d.message = "the program has no END";
      errors_.push_back(d);
    }
    check_open_fors(eof);
    for (const auto& r : refs_) {
      Instruction& in = prog_.code[r.index];
      auto it = prog_.labels.find(in.label);
      if (it == prog_.labels.end()) {
        errors_.push_back({{prog_.file, in.line, r.column}, "label " + in.label + " is not defined"});
        continue;
      }
      const bool target_in_sub = label_region_[in.label];
      if (in.op == Op::Call && !target_in_sub)
        errors_.push_back({{prog_.file, in.line, r.column},
                           "CALL " + in.label + ": a subroutine must be placed after END"});
      if (in.op == Op::Jmp && target_in_sub != r.in_sub)
        errors_.push_back({{prog_.file, in.line, r.column},
                           "JMP " + in.label + " crosses between the main program and a subroutine"});
    }
    prog_.edge_slot_of.resize(prog_.code.size(), ~0u);
    std::sort(errors_.begin(), errors_.end(), [](const Diagnostic& a, const Diagnostic& b) {
      return a.where.line != b.where.line ? a.where.line < b.where.line : a.where.column < b.where.column;
    });
  }

  struct Ref {
    size_t index;
    int column;
    bool in_sub;
  };
  const FunctionTable& fns_;
  Program prog_;
  std::vector<Diagnostic> errors_;
  std::vector<uint32_t> fors_;
  std::vector<Ref> refs_;
  std::map<std::string, bool> label_region_;
  int line_ = 0;
  int end_line_ = 0;
  int depth_ = 0;
  bool network_open_ = false;
  bool after_end_ = false;
  bool in_routine_ = false;
};

}  // namespace

bool parse_constant(std::string_view text, int64_t* value) {
  std::string s(text);
  if (s.empty()) return false;
  bool neg = false;
  size_t i = 0;
  int base = 10;
  std::string u = upper(s);
  if (u[0] == 'K') i = 1;
  else if (u[0] == 'H' && u.size() > 1 && std::isxdigit(static_cast<unsigned char>(u[1]))) { i = 1; base = 16; }
  else if (u.rfind("0X", 0) == 0) { i = 2; base = 16; }
  else if (u.rfind("16#", 0) == 0) { i = 3; base = 16; }
  if (base == 10 && i < u.size() && (u[i] == '-' || u[i] == '+')) {
    neg = u[i] == '-';
    ++i;
  }
  if (i >= u.size()) return false;
  int64_t v = 0;
  for (; i < u.size(); ++i) {
    const char c = u[i];
    int d;
    if (c >= '0' && c <= '9') d = c - '0';
    else if (base == 16 && c >= 'A' && c <= 'F') d = c - 'A' + 10;
    else return false;
    v = v * base + d;
    if (v > 0xFFFFFFFFll) return false;
  }
  *value = neg ? -v : v;
  return true;
}

Program parse_program(std::string_view text, const std::string& file, const FunctionTable& functions) {
  return Parser(file, functions).run(text);
}

Program load_program_file(const std::string& path, const FunctionTable& functions) {
  const std::string why = why_unreadable(path);
  if (!why.empty()) throw SourceError::at(path, 0, 0, "cannot open the program file: " + why);
  std::ifstream f(path);
  if (!f) throw SourceError::at(path, 0, 0, "cannot open the program file");
  std::stringstream ss;
  ss << f.rdbuf();
  return parse_program(ss.str(), path, functions);
}

}  // namespace plc_cell
