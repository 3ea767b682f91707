// Any address text: parsed or refused with a reason; what parses formats and re-parses
// to the same address.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "plc_cell/core/address.h"
#include "plc_cell/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  plc_cell::Address a;
  std::string why;
  if (!plc_cell::try_parse_address(text, &a, &why)) return 0;
  plc_cell::Address b;
  if (!plc_cell::try_parse_address(plc_cell::format_address(a), &b, &why) || !(a == b)) std::abort();
  try {
    plc_cell::check_span(a, 1 + (size & 0xFF));
  } catch (const plc_cell::Error&) {
  }
  return 0;
}
