#pragma once
// What a step's value puts in memory: the same bits on every target.
#include <cstdint>
#include <string>

#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace scenario {

// The raw bits of v for a: a bit 0/1, a register's two's complement for a negative value, a
// float's bits for :f32. Throws Error naming text and the address's range.
uint32_t raw_value(const Address& a, ValueFormat f, const Value& v, const std::string& text);

}  // namespace scenario
}  // namespace plc_cell
