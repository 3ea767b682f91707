#include <algorithm>
#include <cctype>
#include <cstdio>
#include <set>

#include "plc_cell/core/il_parser.h"
#include "plc_cell/mutation/mutant.h"

namespace plc_cell {
namespace mutation {

namespace {

std::string upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string join(const std::vector<std::string>& t) {
  std::string s;
  for (const auto& w : t) s += (s.empty() ? "" : " ") + w;
  return s;
}

bool is_contact(Op op) { return op <= Op::OrDown; }

// v written as the constant `as` was (K10 -> K11, H0F -> H10, 0x0f -> 0x10, 16#F -> 16#10);
// a hexadecimal form has no sign, so a negative value is written in decimal.
std::string constant_like(const std::string& as, int64_t v) {
  const std::string u = upper(as);
  const auto hex = [&](const char* prefix) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%s%llX", prefix, static_cast<unsigned long long>(v));
    return std::string(buf);
  };
  if (u[0] == 'K') return as.substr(0, 1) + std::to_string(v);
  if (v >= 0 && u[0] == 'H') return hex(as.substr(0, 1).c_str());
  if (v >= 0 && u.rfind("0X", 0) == 0) return hex(as.substr(0, 2).c_str());
  if (v >= 0 && u.rfind("16#", 0) == 0) return hex("16#");
  return std::to_string(v);
}

// The mutants of one instruction (its line's words), each as its new words (empty: deleted).
class InstructionMutants {
 public:
  InstructionMutants(const Instruction& in, const std::vector<IlToken>& t, const FunctionTable& fns)
      : in_(in), t_(t), fns_(fns) {
    for (const auto& w : t) words_.push_back(w.text);
  }

  void contact() {
    if (!is_contact(in_.op) || t_.size() < 2) return;
    const std::string m = upper(words_[0]);
    const std::string mod = t_.size() > 2 ? upper(words_[1]) : "";
    const std::string& operand = words_.back();
    if (mod.empty()) add("invert contact", {words_[0], "NOT", operand});
    if (mod == "NOT") add("invert contact", {words_[0], operand});
    if (m == "AND" || m == "OR") {
      std::vector<std::string> o = words_;
      o[0] = m == "AND" ? "OR" : "AND";
      add("AND/OR", o);
    }
    if (mod == "TU" || mod == "TD") {
      add("edge", {words_[0], mod == "TU" ? "TD" : "TU", operand});
      add("edge", {words_[0], operand});
    }
    if (mod.empty()) add("edge", {words_[0], "TU", operand});
  }

  void blocks_and_coils() {
    if (in_.op == Op::AndLd || in_.op == Op::OrLd) add("ANDLD/ORLD", {in_.op == Op::AndLd ? "ORLD" : "ANDLD"});
    if ((in_.op == Op::Set || in_.op == Op::Rst) && words_.size() == 2 &&
        (in_.addr.area == Area::Y || in_.addr.area == Area::M || in_.addr.area == Area::S))
      add("SET/RST", {in_.op == Op::Set ? "RST" : "SET", words_[1]});
    if (in_.op == Op::Out || in_.op == Op::OutNot || in_.op == Op::Set || in_.op == Op::Rst || in_.op == Op::RstReg)
      add("delete coil", {});
  }

  // A TMR/CTR constant preset +1, -1, x2 and /2 within the presets the instruction takes.
  void preset() {
    if ((in_.op != Op::Tmr && in_.op != Op::Ctr) || in_.operands.empty()) return;
    const Operand& p = in_.operands[0];
    if (p.kind != Operand::Kind::Const) return;
    const bool wide = in_.op == Op::Ctr && in_.addr.index >= 200;  // C200-C255 count 32 bits
    const int64_t n = p.k, hi = wide ? 2147483647 : 32767;
    for (int64_t v : {n + 1, n - 1, n * 2, n / 2})
      if (v > 0 && v <= hi && v != n) replace_value(p, v, "preset");
  }

  // Every constant operand of a FUN (whatever form the line gives it: named or positional,
  // K, H or plain, after FUN n, FUN n MNEMONIC or a bare mnemonic) and FOR's count, +1 and
  // -1 within the operand's width; FUN17 CMP's result flags given to another relation.
  void operands() {
    if (in_.op != Op::Fun && in_.op != Op::For) return;
    const FunctionSpec* spec = in_.op == Op::Fun ? fns_.find(in_.fun) : nullptr;
    std::vector<const Operand*> given;
    for (const Operand& o : in_.operands)
      if (o.present && o.column > 0) given.push_back(&o);
    std::sort(given.begin(), given.end(), [](const Operand* a, const Operand* b) { return a->column < b->column; });
    const int64_t lo = in_.is32 ? -2147483648LL : -32768, hi = in_.is32 ? 4294967295LL : 65535;
    for (const Operand* o : given) {
      const size_t slot = size_t(o - in_.operands.data());
      const bool label = spec && slot < spec->operands.size() && spec->operands[slot].role == OperandRole::Label;
      if (o->kind == Operand::Kind::Const && !label)
        for (int64_t v : {o->k + 1, o->k - 1})
          if (v >= lo && v <= hi) replace_value(*o, v, "constant");
      if (in_.op == Op::Fun && in_.fun == 17 && o->kind == Operand::Kind::Bit) comparison(*o, given);
    }
  }

  std::vector<std::pair<std::string, std::vector<std::string>>> out;

 private:
  void add(const char* op, const std::vector<std::string>& words) { out.push_back({op, words}); }

  // The token that holds operand o's value, and where in it the value starts.
  size_t token_of(const Operand& o, size_t* offset) const {
    for (size_t i = 0; i < t_.size(); ++i) {
      const int begin = t_[i].column, end = begin + int(t_[i].text.size());
      if (o.column >= begin && o.column < end) {
        *offset = size_t(o.column - begin);
        return i;
      }
    }
    *offset = 0;
    return t_.size();
  }

  void replace_value(const Operand& o, int64_t v, const char* op) {
    size_t at;
    const size_t i = token_of(o, &at);
    if (i >= t_.size()) return;
    std::vector<std::string> w = words_;
    w[i] = words_[i].substr(0, at) + constant_like(words_[i].substr(at), v);
    add(op, w);
  }

  // EQ=M51 -> GT=M51 and LT=M51 (the relations not given). A flag given by position is
  // moved by writing every operand by name: a positional one after it keeps its slot.
  void comparison(const Operand& flag, const std::vector<const Operand*>& given) {
    const std::string key = upper(flag.name);
    if (key != "EQ" && key != "GT" && key != "LT") return;
    std::set<std::string> taken;
    for (const Operand* o : given) taken.insert(upper(o->name));
    size_t first = t_.size();
    for (const Operand* o : given) {
      size_t at;
      first = std::min(first, token_of(*o, &at));
    }
    size_t at;
    const size_t i = token_of(flag, &at);
    for (const char* other : {"EQ", "GT", "LT"}) {
      if (taken.count(other)) continue;
      if (at > 0) {  // EQ=M51: the key alone changes
        std::vector<std::string> w = words_;
        w[i] = other + words_[i].substr(at - 1);
        add("comparison", w);
        continue;
      }
      std::vector<std::string> w(words_.begin(), words_.begin() + long(first));
      for (const Operand* o : given) {
        size_t from;
        const std::string& token = words_[token_of(*o, &from)];
        w.push_back((o == &flag ? std::string(other) : o->name) + "=" + token.substr(from));
      }
      add("comparison", w);
    }
  }

  const Instruction& in_;
  const std::vector<IlToken>& t_;
  const FunctionTable& fns_;
  std::vector<std::string> words_;
};

}  // namespace

std::vector<Mutant> mutants(const std::vector<std::string>& lines, const Program& program,
                            const FunctionTable& functions) {
  std::vector<Mutant> out;
  for (const Instruction& in : program.code) {
    if (in.line <= 0 || size_t(in.line) > lines.size()) continue;
    const std::vector<IlToken> t = tokenize_il_line(lines[size_t(in.line) - 1]);
    if (t.empty()) continue;
    InstructionMutants im(in, t, functions);
    im.contact();
    im.blocks_and_coils();
    im.preset();
    im.operands();
    std::vector<std::string> words;
    for (const auto& w : t) words.push_back(w.text);
    std::set<std::string> seen;
    for (const auto& [op, w] : im.out) {
      const std::string after = join(w);
      if (!seen.insert(after).second) continue;
      out.push_back({in.line, op, join(words), after});
    }
  }
  return out;
}

std::string apply(const std::vector<std::string>& lines, const Mutant& m) {
  std::string text;
  for (size_t n = 0; n < lines.size(); ++n)
    text += (int(n + 1) == m.line ? m.after : lines[n]) + "\n";
  return text;
}

}  // namespace mutation
}  // namespace plc_cell
