#pragma once
// UTF-8 as plc_cell reads and writes it: YAML files must be Unicode text, and the XML it
// writes (JUnit) must stay well-formed whatever bytes a name or a message carries.
#include <cstddef>
#include <string>
#include <string_view>

namespace plc_cell {
namespace utf8 {

constexpr char32_t kInvalid = 0xFFFFFFFF;

// The code point at s[*i], with *i moved past it. A byte that does not start a valid
// sequence (a stray continuation byte, an overlong form, a surrogate, a value beyond
// U+10FFFF, a sequence cut short) gives kInvalid and moves *i on by that one byte.
char32_t next(std::string_view s, size_t* i);

// c (at most U+10FFFF) appended to out as UTF-8.
void append(char32_t c, std::string* out);

}  // namespace utf8
}  // namespace plc_cell
