// FUN lines: by number (FUN 8 MOV.D) or mnemonic, their modifiers and operands.
#include <cctype>

#include "il_parse.h"

namespace plc_cell {
namespace il {

void Parser::fun_numbered(const std::vector<Token>& toks) {
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

void Parser::fun(const FunctionSpec* spec, const std::string& mods, const Token& at, const std::vector<Token>& toks,
                 size_t first) {
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
  if (!fun_operands(spec, name, is32, toks, first, at, &ops)) return;
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

bool Parser::fun_operands(const FunctionSpec* spec, const std::string& name, bool is32, const std::vector<Token>& toks,
                          size_t first, const Token& at, std::vector<Operand>* out) {
  std::vector<Operand>& ops = *out;
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
  return ok;
}

}  // namespace il
}  // namespace plc_cell
