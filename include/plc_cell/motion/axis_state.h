#pragma once
// What the axis components share about each pulse output PSO0-PSO3: its drive, its
// FUN141 parameters, who holds it and what the status registers show of it.
#include <array>
#include <cstdint>

#include "plc_cell/motion/axis.h"
#include "plc_cell/motion/params.h"

namespace plc_cell {
namespace motion {

constexpr int kAxes = 4;
constexpr uint32_t kFree = UINT32_MAX;  // AxisState::owner of an axis no program holds

struct AxisState {
  Axis axis;
  AxisParams params;
  uint32_t owner = kFree;       // FUN140 instance (or FUN147/148 id) holding the axis
  bool finished = false;        // M1996+n
  int64_t written_pos = 0;      // DR4088 as last written, to see ladder writes
  int64_t rest = 0;             // DR4072 when idle: what a cut/stop left unsent
};
using AxisStates = std::array<AxisState, kAxes>;

}  // namespace motion
}  // namespace plc_cell
