#pragma once
// Registers the temperature, PID and analog instructions (FUN86 TPCTL, FUN30 PID,
// FUN32 ADCNV, FUN33 LCNV, FUN139 HSPWM), and for the FB generation FUN72/73/85 with
// the FB FUN86 in place of the FBs one.
#include "plc_cell/temp/temperature_config.h"

namespace plc_cell {
class FunctionTable;
namespace temp {
void add_temperature_functions(FunctionTable& t, Generation g = Generation::FBs);
}  // namespace temp
}  // namespace plc_cell
