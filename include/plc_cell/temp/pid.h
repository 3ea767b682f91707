#pragma once
// FUN30 PID, the FBs general-purpose loop (manual A:7376-A:7595). The loop's whole
// state lives in its registers (SR, PR, WR), as on the PLC; docs/analog-and-temperature.md
// gives the unit choices the manual leaves open.
namespace plc_cell {

class FunctionTable;

namespace temp {

// Adds FUN30 PID to t.
void add_pid_function(FunctionTable& t);

}  // namespace temp
}  // namespace plc_cell
