// Program flow: labels, JMP and CALL with their regions, RTS/RTI, FOR/NEXT.
#include "il_parse.h"
#include "plc_cell/core/interrupt_sources.h"

namespace plc_cell {
namespace il {

void Parser::check_open_fors(const Token& at) {
  for (size_t i = 0; i < fors_.size(); ++i)
    error(at.column, "FOR on line " + std::to_string(prog_.code[fors_[i]].line) + " has no NEXT");
  fors_.clear();
}

void Parser::flow(const std::string& m, const std::vector<Token>& toks, size_t first) {
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
    label(head, *t);
    return;
  }
  if (m == "JMP" || m == "CALL") {
    const Token* t = operand("a label name");
    if (!t) return;
    jump(m, head, *t);
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

void Parser::label(const Token& head, const Token& t) {
  const std::string name = upper(t.text);
  if (!after_end_ && irq::source_of_label(name) >= 0)
    return error(t.column, name + " is an interrupt label: its routine belongs after END (LBL " + name +
                                " ... RTI)");
  if (prog_.labels.count(name))
    return error(t.column, "label " + t.text + " is defined twice (first on line " +
                                std::to_string(prog_.code[prog_.labels[name]].line) + ")");
  // Inside an open FOR body a label is a jump target within that body, in a routine as
  // in the main program; FOR and NEXT pair by position, and one left open is reported
  // at END or, after END, at the end of the file.
  if (after_end_) in_routine_ = true;
  prog_.labels[name] = static_cast<uint32_t>(prog_.code.size());
  label_region_[name] = after_end_;
  emit(Op::Lbl, head).label = name;
  network_open_ = false;
}

void Parser::jump(const std::string& m, const Token& head, const Token& t) {
  if (!output_ok(head, 1)) return;
  // An interrupt routine runs on its interrupt and returns with RTI: never a jump target.
  if (irq::source_of_label(upper(t.text)) >= 0)
    return error(t.column, m + " " + upper(t.text) + ": " + upper(t.text) +
                                " is an interrupt label; its routine runs on the interrupt, not by " + m);
  Instruction& in = emit(m == "JMP" ? Op::Jmp : Op::Call, head);
  in.label = upper(t.text);
  refs_.push_back({prog_.code.size() - 1, t.column, after_end_});
}

void Parser::check_jumps() {
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
}

}  // namespace il
}  // namespace plc_cell
