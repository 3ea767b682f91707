#include "plc_cell/temp/temp_functions.h"

#include "plc_cell/core/function_table.h"
#include "plc_cell/temp/fb_functions.h"
#include "plc_cell/temp/hspwm.h"
#include "plc_cell/temp/linear_conversion.h"
#include "plc_cell/temp/pid.h"
#include "plc_cell/temp/tpctl.h"

namespace plc_cell {
namespace temp {

void add_temperature_functions(FunctionTable& t, Generation g) {
  if (g == Generation::FB) {
    add_fb_temperature_functions(t);  // FUN72 TP4, FUN73 TSTC, FUN85 TPSNS, FB FUN86
  } else {
    add_tpctl_function(t);
    add_fb_only_notes(t);
  }
  add_pid_function(t);
  add_linear_conversion_functions(t);  // FUN32 ADCNV, FUN33 LCNV
  add_hspwm_function(t);               // FUN139 HSPWM
}

}  // namespace temp
}  // namespace plc_cell
