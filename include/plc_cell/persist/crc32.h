#pragma once
// CRC-32 (IEEE 802.3, the zlib/PNG polynomial): detects torn and corrupt store slots.
#include <cstddef>
#include <cstdint>

namespace plc_cell {
namespace persist {

uint32_t crc32(const void* data, size_t n, uint32_t crc = 0);

}  // namespace persist
}  // namespace plc_cell
