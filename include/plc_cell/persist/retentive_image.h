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

// One range of a stored image and where its values start in the image.
struct StoredRange {
  AreaRange range;
  size_t offset;
};

// Checks the whole image (every header, every bound, every length) without touching any
// memory. Throws Error naming the range and the reason if any part of it is malformed.
std::vector<StoredRange> parse_retentive(const std::vector<uint8_t>& image);

// Writes back every element of a parsed image that lies inside one of `ranges`; returns how
// many. restored_ranges (optional) gets the element ranges written, merged where adjacent.
size_t apply_retentive(const std::vector<uint8_t>& image, const std::vector<StoredRange>& stored,
                       const std::vector<AreaRange>& ranges, Memory* m,
                       std::vector<AreaRange>* restored_ranges = nullptr);

// parse_retentive then apply_retentive: all or nothing of a malformed image is written
// (nothing). Throws Error on a malformed image.
size_t decode_retentive(const std::vector<uint8_t>& image, const std::vector<AreaRange>& ranges, Memory* m);

// "D0-D9,M800-M809" for log lines.
std::string describe_ranges(const std::vector<AreaRange>& ranges);

}  // namespace persist
}  // namespace plc_cell
