// FUN140 HSPSO, FUN141 MPARA, FUN142 PSOFF, FUN143 PSCNV, FUN147 MHSP0, FUN148 MPG: the positioning
// instructions. They act on the MotionUnit installed on the engine (SoftCell
// creates one for every cell); without one they do nothing.
#include "plc_cell/motion/motion_functions.h"

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/motion/interpolation.h"
#include "plc_cell/motion/motion_unit.h"
#include "plc_cell/motion/mpg.h"

namespace plc_cell {
namespace motion {

namespace {
std::string check_ps(const std::vector<plc_cell::Operand>& o) {
  return o[0].k >= 0 && o[0].k <= 3 ? "" : "Ps must be 0-3 (PSO0-PSO3)";
}
std::string check_area(const plc_cell::Operand& o, const char* what) {
  if (o.addr.area != Area::R && o.addr.area != Area::D) return std::string(what) + " must be an R or D register";
  return "";
}
// FUN140 and FUN147 share their shape: EN/PAU/ABT, (Ps|Gp, SR, WR), ACT/ERR/DN.
FunctionSpec program_spec(uint16_t number, const char* mnemonic, const char* first) {
  using R = OperandRole;
  FunctionSpec s;
  s.number = number;
  s.mnemonic = mnemonic;
  s.inputs = {"EN", "PAU", "ABT"};
  s.operands = {{first, R::Const}, {"SR", R::Register}, {"WR", R::Register},
                {"ACT", R::BitOut, true}, {"ERR", R::BitOut, true}, {"DN", R::BitOut, true}};
  s.allow_32 = false;
  s.allow_pulse = false;
  s.always_runs = true;  // EN = 0 stops the output
  return s;
}
template <typename Call>
Call program_call(const ExecContext& c, const BoundOperand* o) {
  Call call;
  call.sr = o[1].addr;
  call.wr = o[2].addr;
  call.en = c.inputs[0];
  call.pau = c.inputs[1];
  call.abt = c.inputs[2];
  call.instance = c.instance;
  return call;
}
template <typename Outputs>
void program_flags(const ExecContext& c, const BoundOperand* o, const Outputs& r) {
  c.flag(o[3], r.act);
  c.flag(o[4], r.err);
  c.flag(o[5], r.dn);
}
std::string check_program(const std::vector<plc_cell::Operand>& o, std::string e) {
  if (e.empty()) e = check_area(o[1], "SR");
  if (e.empty()) e = check_area(o[2], "WR");
  return e;
}

FunctionSpec fun140() {
  FunctionSpec s = program_spec(140, "HSPSO", "Ps");  // run a positioning program on axis Ps
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    auto* u = MotionUnit::of(c.engine);
    if (!u) return;
    Fun140Call call = program_call<Fun140Call>(c, o);
    call.ps = static_cast<int>(o[0].k);
    program_flags(c, o, u->fun140(call, c.now_us));
  };
  s.check = [](const std::vector<plc_cell::Operand>& o) { return check_program(o, check_ps(o)); };
  return s;
}

FunctionSpec fun141() {
  using R = OperandRole;
  FunctionSpec s;
  s.number = 141; s.mnemonic = "MPARA";  // the axis's parameter table (runs whether EN is 0 or 1)
  s.operands = {{"Ps", R::Const}, {"SR", R::Register}, {"ERR", R::BitOut, true}};
  s.allow_32 = false;
  s.allow_pulse = false;
  s.always_runs = true;
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    auto* u = MotionUnit::of(c.engine);
    if (!u) return;
    c.flag(o[2], !u->fun141(static_cast<int>(o[0].k), o[1].addr));
  };
  s.check = [](const std::vector<plc_cell::Operand>& o) {
    std::string e = check_ps(o);
    return e.empty() ? check_area(o[1], "SR") : e;
  };
  return s;
}

FunctionSpec fun142() {
  using R = OperandRole;
  FunctionSpec s;
  s.number = 142; s.mnemonic = "PSOFF";  // force the pulse output of axis N to stop
  s.operands = {{"N", R::Const}};
  s.allow_32 = false;
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    if (auto* u = MotionUnit::of(c.engine)) u->fun142(static_cast<int>(o[0].k), c.now_us);
  };
  s.check = check_ps;
  return s;
}

FunctionSpec fun143() {
  using R = OperandRole;
  FunctionSpec s;
  s.number = 143; s.mnemonic = "PSCNV";  // current position -> Ut, 32-bit D
  s.operands = {{"Ps", R::Const}, {"D", R::Register}};
  s.allow_32 = false;
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    auto* u = MotionUnit::of(c.engine);
    if (!u) return;
    const uint32_t v = static_cast<uint32_t>(u->fun143(static_cast<int>(o[0].k)));
    c.mem.write({o[1].addr.area, Width::Word, o[1].addr.index}, v & 0xFFFF);
    c.mem.write({o[1].addr.area, Width::Word, o[1].addr.index + 1}, v >> 16);
  };
  s.check = [](const std::vector<plc_cell::Operand>& o) {
    std::string e = check_ps(o);
    return e.empty() ? check_area(o[1], "D") : e;
  };
  return s;
}

FunctionSpec fun147() {
  FunctionSpec s = program_spec(147, "MHSP0", "Gp");  // linear interpolation program of group Gp
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    auto* u = MotionUnit::of(c.engine);
    if (!u) return;
    Fun147Call call = program_call<Fun147Call>(c, o);
    call.gp = static_cast<int>(o[0].k);
    program_flags(c, o, u->interpolation().fun147(call, c.now_us * 1000));
  };
  s.check = [](const std::vector<plc_cell::Operand>& o) {
    return check_program(o, o[0].k >= 0 && o[0].k <= 1 ? "" : "Gp must be 0 (Ps0&Ps1, or 3-4 axes) or 1 (Ps2&Ps3)");
  };
  return s;
}

FunctionSpec fun148() {
  using R = OperandRole;
  FunctionSpec s;
  s.number = 148; s.mnemonic = "MPG";  // handwheel on HSC Sc drives axis Ps (run it in a 50 ms ISR)
  s.operands = {{"Sc", R::Source}, {"Ps", R::Source}, {"Fo", R::Register}, {"Mr", R::Register},
                {"WR", R::Register}, {"ACT", R::BitOut, true}};
  s.allow_32 = false;
  s.allow_pulse = false;
  s.always_runs = true;  // with EN = 0 it still follows the counter (nothing accumulates)
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    auto* u = MotionUnit::of(c.engine);
    if (!u) return;
    const auto word = [&](const Address& a, int i) { return c.mem.read({a.area, Width::Word, a.index + i}); };
    Fun148Call call;
    call.sc = static_cast<int>(c.get(o[0]));
    call.ps = static_cast<int>(c.get(o[1]));
    call.fo = static_cast<int32_t>(word(o[2].addr, 0) | (word(o[2].addr, 1) << 16));
    call.fa = static_cast<int16_t>(word(o[3].addr, 0));
    call.fb = static_cast<int16_t>(word(o[3].addr, 1));
    call.wr = o[4].addr;
    call.en = c.en;
    call.instance = c.instance;
    c.flag(o[5], u->mpg().fun148(call, c.now_us * 1000));
  };
  s.check = [](const std::vector<plc_cell::Operand>& o) {
    std::string e;
    if (o[0].kind == plc_cell::Operand::Kind::Const && (o[0].k < 0 || o[0].k > 7)) e = "Sc must be 0-7 (HSC0-HSC7)";
    if (e.empty() && o[1].kind == plc_cell::Operand::Kind::Const) e = check_ps({o[1]});
    if (e.empty()) e = check_area(o[2], "Fo");
    if (e.empty()) e = check_area(o[3], "Mr");
    if (e.empty()) e = check_area(o[4], "WR");
    return e;
  };
  return s;
}

}  // namespace

void add_functions(FunctionTable& t) {
  for (const auto& spec : {fun140(), fun141(), fun142(), fun143(), fun147(), fun148()}) t.add(spec);
}

}  // namespace motion
}  // namespace plc_cell
