// Each instruction's element: contact forms, coils, timers, counters, FUN boxes, flow boxes.
#include "elements.h"

namespace plc_cell {
namespace ladder {

uint64_t address_key(const Address& a) {
  return (uint64_t(a.area) << 40) | (uint64_t(a.width) << 32) | a.index;
}

Names::Names(const Signals& signals) {
  for (const auto& s : signals) names_.emplace(address_key(s.second), s.first);  // the first stays
}

std::string Names::of(const Address& a) const {
  auto it = names_.find(address_key(a));
  return it == names_.end() ? std::string() : it->second;
}

Element Drawer::element(uint32_t i) const {
  const Instruction& in = p_.code[i];
  Element e;
  e.line = in.line;
  e.instruction = static_cast<int>(i);
  if (in.line > 0 && static_cast<size_t>(in.line) < line_comments_.size()) e.comment = line_comments_[in.line];
  switch (in.op) {
    case Op::Out: case Op::OutNot: case Op::Set: case Op::Rst: case Op::RstReg: coil(in, &e); break;
    case Op::Tmr: case Op::Ctr: timer_counter(in, &e); break;
    case Op::Fun: fun(in, &e); break;
    case Op::Jmp: case Op::Call: case Op::Lbl:
      e.type = in.op == Op::Jmp ? "jump" : in.op == Op::Call ? "call" : "label";
      e.label = in.label;
      break;
    case Op::Rts: case Op::Rti: case Op::For: case Op::Next: case Op::End: flow(in, &e); break;
    default: contact(in, &e); break;
  }
  return e;
}

void Drawer::contact(const Instruction& in, Element* e) const {
  e->type = "contact";
  switch (in.op) {
    case Op::OrgNot: case Op::LdNot: case Op::AndNot: case Op::OrNot: e->form = "nc"; break;
    case Op::OrgUp: case Op::LdUp: case Op::AndUp: case Op::OrUp: e->form = "up"; break;
    case Op::OrgDown: case Op::LdDown: case Op::AndDown: case Op::OrDown: e->form = "down"; break;
    default: e->form = "no"; break;
  }
  e->address = format_address(in.addr);
  e->name = names_.of(in.addr);
  e->bit = in.addr;
}

void Drawer::coil(const Instruction& in, Element* e) const {
  e->type = "coil";
  static const char* const forms[] = {"out", "out_not", "set", "rst", "rst"};
  e->form = forms[static_cast<int>(in.op) - static_cast<int>(Op::Out)];
  Address a = in.addr;
  if (in.op == Op::RstReg) {
    a = in.operands.at(0).addr;
    a.width = in.is32 ? Width::DWord : Width::Word;
  }
  e->address = format_address(a);
  e->name = names_.of(a);
}

void Drawer::timer_counter(const Instruction& in, Element* e) const {
  const bool timer = in.op == Op::Tmr;
  e->type = timer ? "timer" : "counter";
  e->address = format_address(in.addr);
  e->name = names_.of(in.addr);
  const Address value{timer ? Area::RT : Area::RC, in.is32 ? Width::DWord : Width::Word, in.addr.index};
  e->values = {e->address, format_address(value)};
  const Operand& pv = in.operands.at(0);
  if (pv.kind == Operand::Kind::Const) {
    e->preset = std::to_string(pv.k);
  } else {
    Address a = pv.addr;
    a.width = in.is32 ? Width::DWord : Width::Word;
    e->preset = e->preset_address = format_address(a);
  }
}

FunOperand Drawer::operand(const Operand& o) const {
  FunOperand f;
  f.name = o.name;
  if (o.kind == Operand::Kind::Const) {
    f.text = o.text.empty() ? "K" + std::to_string(o.k) : o.text;  // a label keeps its name
    return f;
  }
  Address a = o.addr;
  if (o.kind != Operand::Kind::Bit)
    a.width = o.kind == Operand::Kind::Reg32 || o.kind == Operand::Kind::Bits32 ? Width::DWord : Width::Word;
  f.text = f.address = format_address(a);
  f.signal = names_.of(a);
  return f;
}

void Drawer::fun(const Instruction& in, Element* e) const {
  e->type = "fun";
  e->fun = in.fun;
  const FunctionSpec* spec = functions_ ? functions_->find(in.fun) : nullptr;
  e->mnemonic = spec ? spec->mnemonic : "FUN " + std::to_string(in.fun);
  e->pulse = in.pulse;
  e->d32 = in.is32;
  for (const Operand& o : in.operands)
    if (o.present) e->operands.push_back(operand(o));
}

std::vector<std::string> Drawer::fun_inputs(uint32_t i, size_t count) const {
  const FunctionSpec* spec = functions_ ? functions_->find(p_.code[i].fun) : nullptr;
  std::vector<std::string> names;
  for (size_t k = 0; k < count; ++k) {
    if (spec && k < spec->inputs.size()) names.push_back(spec->inputs[k]);
    else names.push_back(k == 0 ? "EN" : "IN" + std::to_string(k + 1));
  }
  return names;
}

void Drawer::flow(const Instruction& in, Element* e) const {
  e->type = "flow";
  static const char* const forms[] = {"RTS", "RTI", "FOR", "NEXT", "END"};
  e->form = forms[static_cast<int>(in.op) - static_cast<int>(Op::Rts)];
  if (in.op == Op::For) {
    FunOperand n = operand(in.operands.at(0));
    n.name = "N";
    e->operands.push_back(n);
  }
}

}  // namespace ladder
}  // namespace plc_cell
