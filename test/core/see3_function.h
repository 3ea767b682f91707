#pragma once
// The native engine's tests (core_tests, the lockstep fuzzer) run the core's FUNs and one of
// their own with three inputs (EN and two LD blocks), as a cell's PID or FUN140 has, without
// its subsystem. It writes what it saw (its EN after .P's edge and its three inputs as they
// came) into its operand, so that an input taken from the wrong block stack level, an edge
// judged differently, or a call made or skipped where the interpreter does not, changes the
// memory.
#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"

namespace plc_cell {
namespace native_test {

// One table for a whole run: the tests and the fuzzer load many programs against it.
inline const FunctionTable& see3_table() {
  static const FunctionTable table = [] {
    FunctionTable t = FunctionTable::with_core_functions();
    FunctionSpec s;
    s.number = 250;
    s.mnemonic = "SEE3";
    s.inputs = {"EN", "B", "C"};
    s.operands = {{"D", OperandRole::Dest}};
    s.always_runs = true;
    s.handler = [](ExecContext& c, const BoundOperand* o) {
      c.put(o[0], c.get(o[0]) * 16 + (c.en | c.inputs[0] << 1 | c.inputs[1] << 2 | c.inputs[2] << 3));
    };
    t.add(s);
    return t;
  }();
  return table;
}

}  // namespace native_test
}  // namespace plc_cell
