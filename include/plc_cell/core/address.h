#pragma once
// One parser and formatter for every address form users and protocols write:
// X0, X0016, WX0008, DWM0000, R100, R00100, DR4088, D12, RT10, RC5, DRC200.
#include <string>
#include <string_view>

#include "plc_cell/core/area.h"

namespace plc_cell {

// Bit: one discrete. Word: a register, or W view of 16 discretes (bit 0 = lowest number).
// DWord: a register pair (low word at the lower address), or DW view of 32 discretes.
enum class Width : uint8_t { Bit, Word, DWord };

struct Address {
  Area area = Area::R;
  Width width = Width::Word;
  uint32_t index = 0;

  bool operator==(const Address& o) const {
    return area == o.area && width == o.width && index == o.index;
  }
  bool operator!=(const Address& o) const { return !(*this == o); }
};

// Throws plc_cell::Error naming the address and the reason.
Address parse_address(std::string_view text);
// Same, without throwing: returns false and fills *why.
bool try_parse_address(std::string_view text, Address* out, std::string* why);

// Short user form: X3, WY8, DWM0, R100, DR4088, RC5, DRC200.
std::string format_address(const Address& a);
// Fixed-width FATEK protocol form: X0003, WY0008, R00100, DR04088, DRC0200.
std::string format_fatek_address(const Address& a);

// How far the index moves from one element to the next: 1 for a bit, 16/32 for W/DW
// views, 2 for a 32-bit register pair, 1 for a 32-bit counter (DRC200, DRC201, ...).
inline uint32_t element_stride(const Address& a) {
  if (is_discrete(a.area)) return a.width == Width::Bit ? 1 : a.width == Width::Word ? 16 : 32;
  if (a.width == Width::DWord && !(a.area == Area::RC && a.index >= kFirst32BitCounter)) return 2;
  return 1;
}

// The n-th element after a: X3+1 = X4, WY8+1 = WY24, DR0+1 = DR2, DRC200+1 = DRC201.
// Throws if the result leaves the area.
Address offset_address(const Address& a, uint32_t n);
// Checks that count elements starting at a stay inside the area; throws otherwise.
void check_span(const Address& a, uint32_t count);

// The stored bits of a value written to one element of a. A bit takes 0 or 1; a 16-bit
// element -32768..65535 and a 32-bit one -2147483648..4294967295: the PLC's signed
// instructions read the same bits as two's complement, so users may write either form.
// Throws naming the address, the allowed range and the value.
uint32_t encode_element(const Address& a, int64_t value);

}  // namespace plc_cell
