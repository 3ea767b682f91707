#pragma once
// The whole memory of a PLC as two flat arrays, the unit a recording stores and compares:
// every discrete's byte (state and DISABLE flag, as core/memory.h keeps them) and every
// register word, area after area in the order of core/area.h.
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/core/memory.h"

namespace plc_cell {
namespace recording {

struct Image {
  std::vector<uint8_t> bits;    // kBitCells bytes
  std::vector<uint16_t> words;  // kWordCells words
};

// Sizes of the two arrays for this build's memory map.
uint32_t bit_cells();
uint32_t word_cells();

// A copy of m (the caller holds the PLC lock: this is the memory copy).
void capture(const Memory& m, Image* out);
// Puts img into m, every area.
void restore(const Image& img, Memory* m);

// The name of cell n of the bits array ("Y0") or of the words array ("D10", "DRC200").
std::string bit_cell_name(uint32_t n);
std::string word_cell_name(uint32_t n);

// The cells that hold a, numbered as a recording's changes number them (the bit cells, then
// bit_cells() + the word cell), in the order Memory::read combines them: lowest bit first,
// low word first. Throws Error naming an address outside the memory.
std::vector<uint32_t> cells_of(const Address& a);
// a's value as Memory::read gives it, from its cells' values (cells_of order; a bit cell's
// value is its byte, state and DISABLE flag).
uint32_t value_of(const Address& a, const std::vector<uint16_t>& cell_values);

// The forced (disabled) discretes of an image, in area order.
std::vector<Address> forced_points(const Image& img);

}  // namespace recording
}  // namespace plc_cell
