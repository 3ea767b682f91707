// The IL text format (docs/program-format.md): lines into statements, END, and the
// whole program's checks; each kind of statement is parsed in a file of its own (il_parse.h).
#include "plc_cell/core/il_parser.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <sstream>

#include "il_parse.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/file_text.h"
#include "plc_cell/core/unreadable.h"

namespace plc_cell {
namespace il {

std::string upper(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace il

std::vector<IlToken> tokenize_il_line(const std::string& line) {
  std::vector<IlToken> out;
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

namespace il {

Program Parser::run(std::string_view text) {
  std::istringstream in{std::string(text)};
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    line_ = n;
    auto toks = tokenize_il_line(line);
    if (!toks.empty()) statement(toks);
  }
  finish();
  if (!errors_.empty()) throw SourceError(errors_);
  return std::move(prog_);
}

void Parser::error(int column, const std::string& msg) {
  errors_.push_back({{prog_.file, line_, column}, msg});
}

Instruction& Parser::emit(Op op, const Token& at) {
  Instruction in;
  in.op = op;
  in.line = line_;
  in.column = at.column;
  prog_.code.push_back(std::move(in));
  return prog_.code.back();
}

void Parser::new_edge_slot() {
  prog_.edge_slot_of.resize(prog_.code.size(), ~0u);
  prog_.edge_slot_of.back() = prog_.edge_slots++;
}

void Parser::statement(const std::vector<Token>& toks) {
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

void Parser::end(const std::vector<Token>& toks) {
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

void Parser::finish() {
  const Token eof{"", 0};
  if (!after_end_) {
    Diagnostic d;
    d.where.file = prog_.file;
    d.where.line = line_;
    d.message = "the program has no END";
    errors_.push_back(d);
  }
  check_open_fors(eof);
  check_jumps();
  prog_.edge_slot_of.resize(prog_.code.size(), ~0u);
  std::sort(errors_.begin(), errors_.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return a.where.line != b.where.line ? a.where.line < b.where.line : a.where.column < b.where.column;
  });
}

}  // namespace il

bool parse_constant(std::string_view text, int64_t* value) {
  std::string s(text);
  if (s.empty()) return false;
  bool neg = false;
  size_t i = 0;
  int base = 10;
  std::string u = il::upper(s);
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
  return il::Parser(file, functions).run(text);
}

Program load_program_file(const std::string& path, const FunctionTable& functions) {
  const std::string why = why_unreadable(path);
  if (!why.empty()) throw SourceError::at(path, 0, 0, "cannot open the program file: " + why);
  const std::optional<std::string> text = file_text(path);
  if (!text) throw SourceError::at(path, 0, 0, "cannot open the program file");
  return parse_program(*text, path, functions);
}

}  // namespace plc_cell
