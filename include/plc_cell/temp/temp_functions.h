#pragma once
// Registers the temperature, PID and analog instructions (FUN86 TPCTL, FUN30 PID,
// FUN32 ADCNV, FUN33 LCNV, FUN139 HSPWM).
namespace plc_cell {
class FunctionTable;
namespace temp {
void add_temperature_functions(FunctionTable& t);
}  // namespace temp
}  // namespace plc_cell
