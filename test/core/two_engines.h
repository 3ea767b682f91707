// The interpreter and the native engine side by side, each on its own memory, loaded with
// the same program: the differential tests' fixture (and the lockstep fuzzer's). A step
// gives both the same inputs and time and reports the first difference, in memory or in
// fault, as text; empty while the two agree.
#pragma once

#include <cstdint>
#include <string>

#include "plc_cell/core/il_parser.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/native/lockstep.h"
#include "plc_cell/core/area.h"

namespace plc_cell {
namespace native_test {

struct TwoEngines {
  const FunctionTable& fns;  // the caller's, for as long as the engines run
  Memory mem_i, mem_n;
  Interpreter interp{mem_i, fns}, native{mem_n, fns};
  Program prog;
  uint64_t now = 0;

  TwoEngines(const FunctionTable& table, const std::string& text, const std::string& file) : fns(table) {
    prog = parse_program(text, file, fns);
    native.use_native(true);
    interp.load(prog);
    native.load(prog);
    for (Memory* m : {&mem_i, &mem_n}) m->set_bit(Area::M, special::kAlwaysOn, true);
  }
  void set_x(uint32_t i, bool v) {
    for (Memory* m : {&mem_i, &mem_n}) m->set_bit(Area::X, i, v);
  }
  void set_inputs(uint16_t x) {
    for (uint32_t i = 0; i < 16; ++i) set_x(i, (x >> i) & 1u);
  }
  // dt_us later, the main program (or the routine X0+I if irq) on both; `what` names the
  // step in the difference. ok is whether the interpreter ran without a fault.
  std::string step(uint32_t dt_us, bool irq, const std::string& what, bool* ok = nullptr) {
    now += dt_us;
    const bool ok_i = irq ? interp.run_routine("X0+I", now, nullptr) : interp.run_main(now, dt_us, nullptr);
    const bool ok_n = irq ? native.run_routine("X0+I", now, nullptr) : native.run_main(now, dt_us, nullptr);
    if (ok) *ok = ok_i;
    if (ok_i != ok_n || interp.fault() != native.fault())
      return "faults differ after " + what + ": interpreter '" + interp.fault() + "', native '" + native.fault() + "'";
    return first_difference(mem_n, mem_i, prog, what);
  }
};

}  // namespace native_test
}  // namespace plc_cell
