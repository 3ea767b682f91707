#pragma once
// The frame check sequence of TRi's multi-point host link (manual §15.4.2): the XOR of
// every character from '@' through the last data character, written as 2 hex digits.
// "@04RVIA" gives 48; "@01RI02" gives 58.
#include <cstdint>
#include <string>
#include <string_view>

namespace plc_cell {
namespace tri {

uint8_t fcs(std::string_view text);
// fcs(text) as two upper-case hex digits.
std::string fcs_hex(std::string_view text);

}  // namespace tri
}  // namespace plc_cell
