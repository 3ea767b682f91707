#include "plc_cell/coverage/report.h"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "plc_cell/core/error.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/coverage/instruction_text.h"
#include "plc_cell/coverage/recorder.h"

namespace plc_cell {
namespace coverage {

namespace {

bool is_contact(Op op) { return op <= Op::OrDown; }
bool starts_network(Op op) { return op == Op::Org || op == Op::OrgNot || op == Op::OrgUp || op == Op::OrgDown; }
// The parser closes the open network at these; what follows needs a new ORG.
bool closes_network(Op op) {
  return starts_network(op) || op == Op::Lbl || op == Op::Rts || op == Op::Rti || op == Op::For || op == Op::Next ||
         op == Op::End;
}

// Which instructions are measured, and under which name.
bool item_of(const Instruction& in, const std::string& fun_name, Item* item) {
  switch (in.op) {
    case Op::AndLd:
    case Op::OrLd:
      return false;
    case Op::Out: case Op::OutNot: case Op::Set: case Op::Rst: case Op::RstReg: case Op::Tmr: case Op::Ctr:
      item->kind = ItemKind::Coil;
      item->name = mnemonic(in) + " " +
                   (in.op == Op::RstReg && !in.operands.empty() ? format_address(in.operands[0].addr) : format_address(in.addr));
      return true;
    case Op::Fun:
      item->kind = ItemKind::Fun;
      item->name = mnemonic(in) + (fun_name.empty() ? "" : " " + fun_name);
      return true;
    case Op::Jmp:
    case Op::Call:
      item->kind = ItemKind::Fun;
      item->name = mnemonic(in) + " " + in.label;
      return true;
    default:
      if (!is_contact(in.op)) return false;
      // M1925 is ON in every scan by definition: a contact on it cannot change, so no
      // test can exercise it and listing it would be noise in every report.
      if (in.addr.area == Area::M && in.addr.index == special::kAlwaysOn) return false;
      item->kind = ItemKind::Contact;
      item->name = format_address(in.addr);
      return true;
  }
}

// The point an item reads or drives, if it is a bit a signal can name.
const Address* point_of(const Instruction& in) {
  if (in.op == Op::RstReg || in.op == Op::Fun || in.op == Op::Jmp || in.op == Op::Call) return nullptr;
  return &in.addr;
}

std::string signal_of(const Instruction& in, const SignalNames& names) {
  const Address* a = point_of(in);
  if (!a) return "";
  for (const auto& n : names)
    if (n.second == *a) return n.first;
  return "";
}

const char* level(bool on) { return on ? "ON" : "OFF"; }

void add_findings(const Network& n, std::vector<Finding>& out) {
  const std::string net = "network " + std::to_string(n.number);
  if (!n.evaluated) {
    out.push_back({n.line, net + " not evaluated"});
    return;  // its instructions were not either: one finding says it
  }
  if (!n.energised) out.push_back({n.line, net + " never energised"});
  for (const Item& it : n.items) {
    const char* what = it.kind == ItemKind::Contact ? "contact " : it.kind == ItemKind::Coil ? "coil " : "";
    if (!it.evaluated()) {
      out.push_back({it.line, what + label(it) + " not evaluated"});
    } else if (!it.exercised()) {
      if (it.kind == ItemKind::Contact)
        out.push_back({it.line, what + label(it) + " never changed (always " + level(it.seen_on) + ")"});
      else if (it.kind == ItemKind::Coil)
        out.push_back({it.line, what + label(it) + " never switched (rung always " + level(it.seen_on) + ")"});
      else
        out.push_back({it.line, label(it) + " never enabled"});
    }
  }
}

void count(const Network& n, Totals& t) {
  ++t.networks;
  t.networks_evaluated += n.evaluated;
  t.networks_energised += n.energised;
  for (const Item& it : n.items) {
    const bool x = it.exercised();
    switch (it.kind) {
      case ItemKind::Contact: ++t.contacts; t.contacts_changed += x; t.contacts_mcdc += it.mcdc; break;
      case ItemKind::Coil: ++t.coils; t.coils_switched += x; break;
      case ItemKind::Fun: ++t.funs; t.funs_enabled += x; break;
    }
  }
}

void read_source(const Program& p, Report& r) {
  std::ifstream in(p.file);
  if (in) {
    std::string line;
    while (std::getline(in, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      r.source.push_back(line);
    }
    if (!in.bad()) return;
  }
  r.source_error = "cannot read " + p.file + ": " + std::strerror(errno);
  r.source.clear();
  for (const Instruction& in : p.code) {
    if (in.line <= 0) continue;
    if (r.source.size() < static_cast<size_t>(in.line)) r.source.resize(static_cast<size_t>(in.line));
    r.source[static_cast<size_t>(in.line) - 1] = instruction_text(in);
  }
}

}  // namespace

std::string label(const Item& it) {
  if (it.signal.empty()) return it.name;
  const size_t sp = it.name.rfind(' ');  // the address is the name's last word
  const std::string address = sp == std::string::npos ? it.name : it.name.substr(sp + 1);
  return (sp == std::string::npos ? "" : it.name.substr(0, sp + 1)) + it.signal + " (" + address + ")";
}

std::vector<Network> networks_of(const Program& p, const std::vector<uint8_t>& seen,
                                 const std::vector<std::string>& fun_names, const SignalNames& names) {
  std::vector<Network> networks;
  std::string routine;
  Network* open = nullptr;
  for (size_t i = 0; i < p.code.size(); ++i) {
    const Instruction& in = p.code[i];
    if (in.op == Op::Lbl && i > p.main_end) routine = in.label;
    if (closes_network(in.op)) open = nullptr;
    if (starts_network(in.op)) {
      networks.emplace_back();
      open = &networks.back();
      open->number = static_cast<uint32_t>(networks.size());
      open->line = in.line;
      open->routine = routine;
      open->evaluated = seen[i] != 0;
    }
    if (!open) continue;
    open->end_line = in.line;
    Item item;
    if (!item_of(in, fun_names[i], &item)) continue;
    item.signal = signal_of(in, names);
    item.index = static_cast<uint32_t>(i);
    item.line = in.line;
    item.seen_off = seen[i] & Interpreter::kSeenOff;
    item.seen_on = seen[i] & Interpreter::kSeenOn;
    if (item.kind != ItemKind::Contact && item.seen_on) open->energised = true;
    open->items.push_back(item);
  }
  return networks;
}

Report report(const Recorder& rec) {
  const Program& p = rec.program();
  Report r;
  r.file = p.file;
  r.runs = rec.runs();
  r.networks = networks_of(p, rec.seen(), rec.fun_names(), rec.signal_names());
  for (size_t n = 0; n < r.networks.size(); ++n) {
    size_t k = 0;
    for (Item& it : r.networks[n].items)
      if (it.kind == ItemKind::Contact) it.mcdc = rec.independent(n, k++);
  }
  for (const Network& n : r.networks) {
    count(n, r.totals);
    add_findings(n, r.findings);
  }
  read_source(p, r);
  return r;
}

}  // namespace coverage
}  // namespace plc_cell
