#pragma once
// The counters subsystem's instructions: FUN92 HSCTR, FUN93 HSCTW, FUN145 EN, FUN146 DIS
// and FUN74 IMDIO. A cell's instruction set is SoftCell::functions(); a table made here
// reaches the HscUnit attached to the PLC that runs it (HscUnit::of).
#include "plc_cell/core/function_table.h"

namespace plc_cell {
namespace hsc {

void add_functions(FunctionTable& t);

}  // namespace hsc
}  // namespace plc_cell
