// FUN92 HSCTR, FUN93 HSCTW, FUN145 EN, FUN146 DIS and FUN74 IMDIO: the
// instructions of the high-speed counter and interrupt subsystem.
#include "plc_cell/hsc/hsc_functions.h"

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/hsc/hsc_unit.h"

namespace plc_cell {
namespace hsc {

namespace {
std::string check_cn(const std::vector<Operand>& o) {
  return o[0].k >= 0 && o[0].k <= 4 ? "" : "CN must be 0-3 (HSC0-3/HST0-3) or 4 (HSTA)";
}
}  // namespace

void add_functions(FunctionTable& t) {
  using R = OperandRole;
  FunctionSpec s;

  s = {};
  s.number = 92; s.mnemonic = "HSCTR";  // chip CV -> CPU CV register (CN 0-3 HSC/HST, 4 HSTA)
  s.operands = {{"CN", R::Const}};
  s.allow_32 = false;
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    if (auto* u = HscUnit::of(c.engine)) u->read_chip(static_cast<int>(o[0].k));
  };
  s.check = check_cn;
  t.add(s);

  s = {};
  s.number = 93; s.mnemonic = "HSCTW";  // CPU CV (D=0) or PV (D=1) register -> chip
  s.operands = {{"CN", R::Const}, {"D", R::Const}};
  s.allow_32 = false;
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    if (auto* u = HscUnit::of(c.engine)) u->write_chip(static_cast<int>(o[0].k), o[1].k != 0);
  };
  s.check = [](const std::vector<Operand>& o) {
    const std::string cn = check_cn(o);
    if (!cn.empty()) return cn;
    return o[1].k == 0 || o[1].k == 1 ? std::string() : std::string("D must be 0 (CV) or 1 (PV)");
  };
  t.add(s);

  for (int en = 1; en >= 0; --en) {
    s = {};
    s.number = en ? 145 : 146; s.mnemonic = en ? "EN" : "DIS";  // enable/disable an interrupt by label
    s.operands = {{"LBL", R::Label}};
    s.allow_32 = false;
    s.handler = [en](ExecContext& c, const BoundOperand* o) {
      if (auto* u = HscUnit::of(c.engine)) u->set_enabled(o[0].text, en != 0);
    };
    s.check = [](const std::vector<Operand>& o) {
      const int src = source_of_label(o[0].text);
      if (src < 0) return "'" + o[0].text + "' is not an interrupt label (e.g. X0+I, HSC0I, HST1I, HSTAI)";
      if (src >= kTimeBase0 && src < kHsc0I) return std::string("time-base interrupts are switched by R4162");
      return std::string();
    };
    t.add(s);
  }

  s = {};
  s.number = 74; s.mnemonic = "IMDIO";  // immediate refresh of N inputs or outputs from D
  s.operands = {{"D", R::BitIn}, {"N", R::Const}};
  s.allow_32 = false;
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    if (auto* u = HscUnit::of(c.engine)) u->immediate_io(o[0].addr, static_cast<uint32_t>(o[1].k));
  };
  s.check = [](const std::vector<Operand>& o) {
    if (o[0].addr.area != Area::X && o[0].addr.area != Area::Y) return std::string("D must be an input X or output Y");
    if (o[1].k < 1 || o[0].addr.index + o[1].k > 256) return std::string("N must be 1 or more, within X/Y0-255");
    return std::string();
  };
  t.add(s);
}

}  // namespace hsc
}  // namespace plc_cell
