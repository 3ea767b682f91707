#pragma once
// Registers the temperature and PID instructions (FUN86 TPCTL, FUN30 PID).
namespace plc_cell {
class FunctionTable;
namespace temp {
void add_temperature_functions(FunctionTable& t);
}  // namespace temp
}  // namespace plc_cell
