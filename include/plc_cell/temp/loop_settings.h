#pragma once
// A change to the set point and gains of a FUN86 loop of modules.temperature.loops (what
// plc_node's ~set_pid_loop asks for), checked before anything is written: a refused change
// writes nothing, and the reason names the field, its range and the value given.
#include <cstdint>
#include <limits>
#include <string>

#include "plc_cell/core/memory.h"
#include "plc_cell/temp/temperature_config.h"

namespace plc_cell {
namespace temp {

struct LoopChange {
  double setpoint = std::numeric_limits<double>::quiet_NaN();  // degrees in the modules' unit; NaN: unchanged
  int32_t kc = -1, ki = -1, td = -1;                           // -1: unchanged
};

// The set point register holds 0.1 degree in 16 bits.
constexpr double kSetpointMin = -3276.8, kSetpointMax = 3276.7;
constexpr int32_t kGainMax = 9999;

// "" when the change can be applied, else e.g. "setpoint 4000.0 °C out of range -3276.8..3276.7".
std::string check_loop_change(const LoopDef& loop, const LoopChange& change, bool fahrenheit);
// Writes a checked change into the loop's registers (call under the PLC lock).
void apply_loop_change(const LoopDef& loop, const LoopChange& change, Memory& mem);

}  // namespace temp
}  // namespace plc_cell
