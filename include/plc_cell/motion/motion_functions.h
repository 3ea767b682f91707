#pragma once
// The positioning subsystem's instructions: FUN140-FUN143 (pulse axes), FUN147/148 (MPG)
// and the interpolation FUNs. A cell's instruction set is SoftCell::functions(); a table
// made here reaches the MotionUnit attached to the PLC that runs it (MotionUnit::of).
#include "plc_cell/core/function_table.h"

namespace plc_cell {
namespace motion {

void add_functions(FunctionTable& t);

}  // namespace motion
}  // namespace plc_cell
