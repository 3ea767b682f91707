#include "plc_cell/tri/fcs.h"

namespace plc_cell {
namespace tri {

uint8_t fcs(std::string_view text) {
  uint8_t x = 0;
  for (char c : text) x ^= uint8_t(c);
  return x;
}

std::string fcs_hex(std::string_view text) {
  static const char* kHex = "0123456789ABCDEF";
  const uint8_t x = fcs(text);
  return {kHex[x >> 4], kHex[x & 15]};
}

}  // namespace tri
}  // namespace plc_cell
