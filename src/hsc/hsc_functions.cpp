// FUN92 HSCTR, FUN93 HSCTW, FUN145 EN, FUN146 DIS and FUN74 IMDIO: the
// instructions of the high-speed counter and interrupt subsystem.
#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/hsc/hsc_unit.h"

namespace plc_cell {
namespace hsc {

void install_functions(FunctionTable& t) {
  using R = OperandRole;
  FunctionSpec s;

  s = {};
  s.number = 92; s.mnemonic = "HSCTR";  // chip CV -> CPU CV register (CN 0-3 HSC/HST, 4 HSTA)
  s.operands = {{"CN", R::Const}};
  s.allow_32 = false;
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    if (auto* u = HscUnit::of(c.engine)) u->read_chip(static_cast<int>(o[0].k));
  };
  t.add(s);

  s = {};
  s.number = 93; s.mnemonic = "HSCTW";  // CPU CV (D=0) or PV (D=1) register -> chip
  s.operands = {{"CN", R::Const}, {"D", R::Const}};
  s.allow_32 = false;
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    if (auto* u = HscUnit::of(c.engine)) u->write_chip(static_cast<int>(o[0].k), o[1].k != 0);
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
    t.add(s);
  }

  s = {};
  s.number = 74; s.mnemonic = "IMDIO";  // immediate refresh of N inputs or outputs from D
  s.operands = {{"D", R::BitIn}, {"N", R::Const}};
  s.allow_32 = false;
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    if (auto* u = HscUnit::of(c.engine)) u->immediate_io(o[0].addr, static_cast<uint32_t>(o[1].k));
  };
  t.add(s);
}

namespace {
const bool installed = (FunctionTable::add_installer(&install_functions), true);
}  // namespace

}  // namespace hsc
}  // namespace plc_cell
