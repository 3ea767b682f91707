#include "plc_cell/persist/crc32.h"

#include <zlib.h>

namespace plc_cell {
namespace persist {

// zlib's CRC-32 (same polynomial, "braided": several bytes per step): the scan hook
// checksums the whole retentive image (~33 kB by default) whenever it changed.
uint32_t crc32(const void* data, size_t n, uint32_t crc) {
  const auto* p = static_cast<const Bytef*>(data);
  uLong c = crc;
  while (n > 0) {
    const uInt chunk = n > 0x40000000u ? 0x40000000u : uInt(n);
    c = ::crc32(c, p, chunk);
    p += chunk;
    n -= chunk;
  }
  return uint32_t(c);
}

}  // namespace persist
}  // namespace plc_cell
