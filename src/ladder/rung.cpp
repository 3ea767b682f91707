// A network's instructions as series/parallel expressions and output groups (rung.h).
#include "rung.h"

#include <algorithm>

namespace plc_cell {
namespace ladder {

namespace {

enum class Place { Org, Ld, And, Or };

Place place_of(Op op) {
  switch (op) {
    case Op::Org: case Op::OrgNot: case Op::OrgUp: case Op::OrgDown: return Place::Org;
    case Op::Ld: case Op::LdNot: case Op::LdUp: case Op::LdDown: return Place::Ld;
    case Op::And: case Op::AndNot: case Op::AndUp: case Op::AndDown: return Place::And;
    default: return Place::Or;
  }
}

ExprP combine(Expr::Kind kind, const ExprP& a, const ExprP& b) {
  auto e = std::make_shared<Expr>();
  e->kind = kind;
  for (const ExprP& x : {a, b}) {
    if (x->kind == kind) e->parts.insert(e->parts.end(), x->parts.begin(), x->parts.end());
    else e->parts.push_back(x);
  }
  return e;
}

bool contains(const ExprP& e, const ExprP& x) {
  if (e == x) return true;
  return std::any_of(e->parts.begin(), e->parts.end(), [&](const ExprP& p) { return contains(p, x); });
}

std::string where(const Program& p, uint32_t i) { return "line " + std::to_string(p.code[i].line); }

struct Output {
  uint32_t instruction;
  ExprP expr;
};

// The interpreter's evaluation with expressions for values.
struct Evaluation {
  const Program& p;
  ExprP acc;
  std::vector<ExprP> stack;
  std::vector<Output> outputs;
  std::string reason;
  bool called = false;     // a CALL ran: what follows sees the routine's result
  bool fun_inputs = false; // a FUN with several inputs took the rung

  void fail(const std::string& why) {
    if (reason.empty()) reason = why;
  }
  void contact(uint32_t i);
  void output(uint32_t i, Rung* rung);
};

void Evaluation::contact(uint32_t i) {
  const Op op = p.code[i].op;
  if (op == Op::AndLd || op == Op::OrLd) {
    if (stack.empty()) return fail(where(p, i) + ": " + (op == Op::AndLd ? "ANDLD" : "ORLD") + " without a block");
    const ExprP top = stack.back();
    stack.pop_back();
    acc = op == Op::AndLd ? series(top, acc) : parallel(top, acc);
    return;
  }
  if (fun_inputs) return fail(where(p, i) + ": a contact after a FUN with several inputs extends its EN input, "
                                           "whose branch would cross the FUN's other inputs");
  const ExprP c = contact_expr(i);
  switch (place_of(op)) {
    case Place::Org: acc = c; stack.clear(); break;
    case Place::Ld: stack.push_back(acc); acc = c; break;
    case Place::And: acc = series(acc, c); break;
    case Place::Or: acc = parallel(acc, c); break;
  }
}

void Evaluation::output(uint32_t i, Rung* rung) {
  if (called) fail(where(p, i) + ": this output follows a CALL on the same network, so its input is "
                                 "whatever the subroutine left, not a rung that can be drawn");
  if (fun_inputs) fail(where(p, i) + ": this output reuses the EN input of the FUN with several inputs "
                                     "before it; its branch would cross the FUN's other inputs");
  if (!stack.empty() && p.code[i].op == Op::Fun) {
    if (!outputs.empty())
      fail(where(p, i) + ": a FUN with several inputs after another output: its inputs would cross "
                         "the rung's branches");
    rung->fun_inputs = stack;
    rung->fun_inputs.push_back(acc);
    rung->fun = i;
    acc = stack.front();  // the result after it is its EN input
    stack.clear();
    fun_inputs = true;
    return;
  }
  if (!stack.empty()) fail(where(p, i) + ": an LD block is still open at this output");
  outputs.push_back({i, acc});
  if (p.code[i].op == Op::Call) called = true;
}

// Parts of `e` after the parts of `prev`, when `e` is `prev` extended in series.
bool extension_of(const ExprP& prev, const ExprP& e, std::vector<ExprP>* ext) {
  std::vector<ExprP> head = prev->kind == Expr::Kind::Series ? prev->parts : std::vector<ExprP>{prev};
  if (e->kind != Expr::Kind::Series || e->parts.size() <= head.size()) return false;
  if (!std::equal(head.begin(), head.end(), e->parts.begin())) return false;
  ext->assign(e->parts.begin() + static_cast<long>(head.size()), e->parts.end());
  return std::none_of(ext->begin(), ext->end(), [&](const ExprP& x) { return contains(x, prev); });
}

void group(Evaluation& ev, Rung* rung) {
  ExprP last;
  for (const Output& o : ev.outputs) {
    if (o.expr == last) {
      rung->groups.back().outputs.push_back(o.instruction);
      continue;
    }
    Group g;
    if (!last) g.extension = {o.expr};
    else if (!extension_of(last, o.expr, &g.extension))
      ev.fail(where(ev.p, o.instruction) + ": the result reaching this output is not the rung of the outputs "
                                           "above extended in series (an OR or ORLD after an output would "
                                           "also feed the outputs above it), so it has no planar ladder");
    g.outputs.push_back(o.instruction);
    rung->groups.push_back(std::move(g));
    last = o.expr;
  }
  if (ev.acc && ev.acc != last && !ev.fun_inputs) {  // contacts after the last output drive nothing
    Group g;
    if (!last) g.extension = {ev.acc};
    else if (!extension_of(last, ev.acc, &g.extension))
      ev.fail("the contacts after the last output do not extend its rung in series");
    rung->groups.push_back(std::move(g));
  }
}

}  // namespace

ExprP contact_expr(uint32_t instruction) {
  auto e = std::make_shared<Expr>();
  e->instruction = instruction;
  return e;
}

ExprP series(const ExprP& a, const ExprP& b) { return combine(Expr::Kind::Series, a, b); }
ExprP parallel(const ExprP& a, const ExprP& b) { return combine(Expr::Kind::Parallel, a, b); }

bool is_contact(Op op) { return op <= Op::OrLd; }
bool is_output(Op op) { return (op >= Op::Out && op <= Op::Fun) || op == Op::Jmp || op == Op::Call; }
bool is_flow(Op op) { return op >= Op::Lbl && !is_output(op); }

Rung build_rung(const Program& p, uint32_t first, uint32_t end) {
  Rung rung;
  Evaluation ev{p, nullptr, {}, {}, {}, false, false};
  for (uint32_t i = first; i < end; ++i) {
    if (is_contact(p.code[i].op)) ev.contact(i);
    else ev.output(i, &rung);
  }
  if (!ev.stack.empty())
    ev.fail(std::to_string(ev.stack.size()) + " LD block(s) left open at the end of the network: "
            "no ANDLD or ORLD joins them to the rung");
  group(ev, &rung);
  rung.reason = ev.reason;
  return rung;
}

}  // namespace ladder
}  // namespace plc_cell
