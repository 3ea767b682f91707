#pragma once
// Internal to the temperature instructions: a Y point of a FUN's output operand, written as
// a coil is (a disabled, that is forced, point keeps its state).
#include <cstdint>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/memory.h"

namespace plc_cell {
namespace temp {

inline void set_y(const BoundOperand& y, uint32_t i, bool v) {
  uint8_t& b = y.b[i];
  if (!(b & kBitDisabled)) b = v ? kBitState : 0;
}

}  // namespace temp
}  // namespace plc_cell
