#include "input_cone.h"

#include <map>
#include <set>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace mutation {

namespace {

// A memory element: a discrete, or a register word (bit 63 set).
using Element = uint64_t;
Element bit_element(Area a, uint32_t i) { return (uint64_t(a) << 32) | i; }
Element word_element(Area a, uint32_t i) { return (1ULL << 63) | (uint64_t(a) << 32) | i; }
bool is_input(Element e) { return !(e >> 63) && Area((e >> 32) & 0xFF) == Area::X; }
uint32_t index_of(Element e) { return uint32_t(e); }

// The clock relays and the first-scan pulse change with time alone, M1925 never: none is
// an input the search drives.
bool is_clock(Element e) {
  return !(e >> 63) && Area((e >> 32) & 0xFF) == Area::M && index_of(e) >= special::kClock10ms &&
         index_of(e) <= special::kAlwaysOn;
}

struct Access {
  std::set<Element> reads, writes;
  bool open = false;
};

bool starts_network(Op op) { return op == Op::Org || op == Op::OrgNot || op == Op::OrgUp || op == Op::OrgDown; }

// The elements an operand spans.
std::vector<Element> elements(const Operand& o, uint8_t span) {
  std::vector<Element> out;
  const uint32_t n = span ? span : 1;
  switch (o.kind) {
    case Operand::Kind::Const: break;
    case Operand::Kind::Bit: out.push_back(bit_element(o.addr.area, o.addr.index)); break;
    case Operand::Kind::Reg16:
    case Operand::Kind::Reg32:
      for (uint32_t k = 0; k < n * (o.kind == Operand::Kind::Reg32 ? 2 : 1); ++k)
        out.push_back(word_element(o.addr.area, o.addr.index + k));
      break;
    case Operand::Kind::Bits16:
    case Operand::Kind::Bits32:
      for (uint32_t k = 0; k < n * (o.kind == Operand::Kind::Bits32 ? 32 : 16); ++k)
        out.push_back(bit_element(o.addr.area, o.addr.index + k));
      break;
  }
  return out;
}

void fun_access(const Instruction& in, const FunctionTable& functions, Access* a) {
  static const FunctionTable core = FunctionTable::with_core_functions();
  const FunctionSpec* spec = functions.find(in.fun);
  if (!spec || !core.find(in.fun)) a->open = true;  // an extension's FUN acts beyond its operands
  if (!spec) return;
  for (size_t s = 0; s < in.operands.size() && s < spec->operands.size(); ++s) {
    const Operand& o = in.operands[s];
    if (!o.present) continue;
    const OperandRole role = spec->operands[s].role;
    for (Element e : elements(o, spec->operands[s].span)) {
      if (role == OperandRole::Source || role == OperandRole::BitIn || role == OperandRole::Register) a->reads.insert(e);
      if (role == OperandRole::Dest || role == OperandRole::BitOut || role == OperandRole::Register) a->writes.insert(e);
    }
  }
}

void access(const Instruction& in, const FunctionTable& functions, Access* a) {
  if (in.op <= Op::OrDown) {
    a->reads.insert(bit_element(in.addr.area, in.addr.index));
    return;
  }
  switch (in.op) {
    case Op::AndLd: case Op::OrLd: case Op::End: return;
    case Op::Out: case Op::OutNot: case Op::Set: case Op::Rst:
      a->writes.insert(bit_element(in.addr.area, in.addr.index));
      if (in.addr.area == Area::T || in.addr.area == Area::C)  // RST of a timer or counter: its value too
        a->writes.insert(word_element(in.addr.area == Area::T ? Area::RT : Area::RC, in.addr.index));
      return;
    case Op::RstReg:
      for (const Operand& o : in.operands)
        for (Element e : elements(o, 1)) a->writes.insert(e);
      return;
    case Op::Tmr: case Op::Ctr:
      for (const Operand& o : in.operands)
        for (Element e : elements(o, 1)) a->reads.insert(e);
      a->writes.insert(bit_element(in.addr.area, in.addr.index));
      a->writes.insert(word_element(in.op == Op::Tmr ? Area::RT : Area::RC, in.addr.index));
      return;
    case Op::Fun: return fun_access(in, functions, a);
    default: a->open = true;  // jumps, calls, labels, loops, returns
  }
}

Address address_of(Element e) {
  const Area area = Area((e >> 32) & 0xFF);
  return Address{area, (e >> 63) ? Width::Word : Width::Bit, index_of(e)};
}

}  // namespace

std::vector<Address> written_by(const Program& program, const FunctionTable& functions) {
  Access all;
  for (const Instruction& in : program.code) access(in, functions, &all);
  std::vector<Address> out;
  for (Element e : all.writes) {
    const Address a = address_of(e);
    try {
      check_span(a, 1);  // a 32-bit counter's high word is its own element
      out.push_back(a);
    } catch (const Error&) {
    }
  }
  return out;
}

std::vector<NetworkInputs> network_inputs(const Program& program, const FunctionTable& functions) {
  // The networks as coverage divides them (coverage/report.cpp): an ORG starts one, and a
  // label, a return, FOR, NEXT or END ends it.
  // A jump, a call or a loop in the main program decides which networks run and how often
  // from what its own network reads: no network's cone shows that.
  bool flow = false;
  for (size_t i = 0; i < program.code.size() && i <= program.main_end; ++i)
    flow = flow || program.code[i].op == Op::Jmp || program.code[i].op == Op::Call || program.code[i].op == Op::For;
  std::vector<NetworkInputs> nets;
  std::vector<Access> acc;
  bool open_net = false;
  for (size_t i = 0; i < program.code.size(); ++i) {
    const Instruction& in = program.code[i];
    if (starts_network(in.op)) {
      nets.emplace_back();
      nets.back().line = in.line;
      acc.emplace_back();
      acc.back().open = flow || i > program.main_end;  // a routine runs when it is called or its event comes
      open_net = true;
    } else if (in.op == Op::Lbl || in.op == Op::Rts || in.op == Op::Rti || in.op == Op::For || in.op == Op::Next ||
               in.op == Op::End) {
      open_net = false;
    }
    if (!open_net) continue;
    nets.back().end_line = in.line;
    access(in, functions, &acc.back());
  }
  std::map<Element, std::vector<size_t>> writers;
  for (size_t n = 0; n < acc.size(); ++n)
    for (Element e : acc[n].writes) writers[e].push_back(n);
  for (size_t n = 0; n < nets.size(); ++n) {
    std::set<uint32_t> x;
    std::set<size_t> seen{n};
    std::vector<size_t> todo{n};
    bool closed = true;
    while (!todo.empty()) {
      const size_t m = todo.back();
      todo.pop_back();
      closed = closed && !acc[m].open;
      for (Element e : acc[m].reads) {
        if (is_input(e)) x.insert(index_of(e));
        if (is_input(e) || is_clock(e)) continue;
        const auto w = writers.find(e);
        if (w == writers.end()) {
          closed = false;  // read, never written by the program: the outside or the system sets it
          continue;
        }
        for (size_t k : w->second)
          if (seen.insert(k).second) todo.push_back(k);
      }
    }
    nets[n].x.assign(x.begin(), x.end());
    nets[n].closed = closed;
  }
  return nets;
}

}  // namespace mutation
}  // namespace plc_cell
