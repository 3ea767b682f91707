#include "plc_cell/temp/temp_functions.h"

#include "plc_cell/core/function_table.h"
#include "plc_cell/temp/pid.h"
#include "plc_cell/temp/tpctl.h"

namespace plc_cell {
namespace temp {

void add_temperature_functions(FunctionTable& t) {
  add_tpctl_function(t);
  add_pid_function(t);
}

}  // namespace temp
}  // namespace plc_cell
