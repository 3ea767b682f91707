#pragma once
// Which inputs of the cell a network's result depends on: the inputs (X) it reads, and,
// through the relays, timers, counters and registers it reads that other networks write,
// theirs in turn. The mutation search drives these inputs through every combination when
// they are few (input_search.h).
#include <cstdint>
#include <vector>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/program.h"

namespace plc_cell {
namespace mutation {

struct NetworkInputs {
  int line = 0, end_line = 0;  // its first and last instruction
  std::vector<uint32_t> x;     // X0 = 0, X1 = 1, ...: the inputs of its cone, ascending
  // Everything the cone reads is an input, a constant, a clock relay (M1920-M1925) or
  // written by a network of the main program, and no network of it jumps, calls, loops or
  // runs a FUN of an extension (whose effects its operands do not show): x is the whole
  // story. False: an exhaustive search over x would not be one.
  bool closed = true;
};

// Every memory element an instruction of the program writes, each once: the coils, each
// timer's and counter's bit and value, the destinations and flags of its FUNs (a register
// by its words, a W/DW view by its bits).
std::vector<Address> written_by(const Program& program, const FunctionTable& functions);

// The networks of the program (an ORG starts one), routines included, in program order.
std::vector<NetworkInputs> network_inputs(const Program& program, const FunctionTable& functions);

}  // namespace mutation
}  // namespace plc_cell
