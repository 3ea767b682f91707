#include "plc_cell/core/utf8.h"

namespace plc_cell {
namespace utf8 {

char32_t next(std::string_view s, size_t* i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(*i);
  if (b < 0x80) return static_cast<char32_t>(s[(*i)++]);
  size_t n;
  char32_t c, min;
  if ((b & 0xE0) == 0xC0) n = 1, c = b & 0x1F, min = 0x80;
  else if ((b & 0xF0) == 0xE0) n = 2, c = b & 0x0F, min = 0x800;
  else if ((b & 0xF8) == 0xF0) n = 3, c = b & 0x07, min = 0x10000;
  else return ++*i, kInvalid;
  if (*i + n >= s.size()) return ++*i, kInvalid;  // cut short
  for (size_t k = 1; k <= n; ++k) {
    if ((byte(*i + k) & 0xC0) != 0x80) return ++*i, kInvalid;
    c = (c << 6) | (byte(*i + k) & 0x3F);
  }
  if (c < min || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) return ++*i, kInvalid;
  *i += n + 1;
  return c;
}

void append(char32_t c, std::string* out) {
  if (c < 0x80) {
    *out += static_cast<char>(c);
  } else if (c < 0x800) {
    *out += static_cast<char>(0xC0 | (c >> 6));
    *out += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    *out += static_cast<char>(0xE0 | (c >> 12));
    *out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    *out += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    *out += static_cast<char>(0xF0 | (c >> 18));
    *out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
    *out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    *out += static_cast<char>(0x80 | (c & 0x3F));
  }
}

}  // namespace utf8
}  // namespace plc_cell
