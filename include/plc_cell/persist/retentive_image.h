#pragma once
// The retentive ranges as bytes: what a store slot holds. Each range is written with
// its bounds, so a store from an older config restores exactly the elements both share.
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/core/memory.h"

namespace plc_cell {
namespace persist {

// Appends the ranges' contents to out (cleared first). Discretes: 1 byte each (state only,
// not the force flag). Registers: 2 bytes little-endian (32-bit counters as their two words).
void encode_retentive(const std::vector<AreaRange>& ranges, const Memory& m, std::vector<uint8_t>* out);

// Writes back every stored element that lies inside one of `ranges`. Returns how many
// elements were restored; throws Error on a malformed image.
size_t decode_retentive(const std::vector<uint8_t>& image, const std::vector<AreaRange>& ranges, Memory* m);

}  // namespace persist
}  // namespace plc_cell
