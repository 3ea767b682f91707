#include "plc_cell/core/address.h"

#include <cctype>
#include <cstdio>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace {

struct Prefix {
  const char* text;
  Area area;
  Width width;
};

// Longest prefixes first, so that DWM beats D and DR beats D.
const Prefix kPrefixes[] = {
    {"DWX", Area::X, Width::DWord}, {"DWY", Area::Y, Width::DWord}, {"DWM", Area::M, Width::DWord},
    {"DWS", Area::S, Width::DWord}, {"DWT", Area::T, Width::DWord}, {"DWC", Area::C, Width::DWord},
    {"DRT", Area::RT, Width::DWord}, {"DRC", Area::RC, Width::DWord}, {"DR", Area::R, Width::DWord},
    {"DD", Area::D, Width::DWord},   {"DF", Area::F, Width::DWord},   {"WX", Area::X, Width::Word},
    {"WY", Area::Y, Width::Word},    {"WM", Area::M, Width::Word},    {"WS", Area::S, Width::Word},
    {"WT", Area::T, Width::Word},    {"WC", Area::C, Width::Word},    {"RT", Area::RT, Width::Word},
    {"RC", Area::RC, Width::Word},   {"X", Area::X, Width::Bit},      {"Y", Area::Y, Width::Bit},
    {"M", Area::M, Width::Bit},      {"S", Area::S, Width::Bit},      {"T", Area::T, Width::Bit},
    {"C", Area::C, Width::Bit},      {"R", Area::R, Width::Word},     {"D", Area::D, Width::Word},
    {"F", Area::F, Width::Word},
};

bool starts_with_ci(std::string_view s, const char* p) {
  size_t i = 0;
  for (; p[i]; ++i) {
    if (i >= s.size() || std::toupper(static_cast<unsigned char>(s[i])) != p[i]) return false;
  }
  return true;
}

// Last element index that the address may start at, or a reason it cannot exist.
bool span_ok(const Address& a, uint32_t count, std::string* why) {
  const uint32_t size = area_size(a.area);
  uint64_t last = 0;
  if (is_discrete(a.area)) {
    const uint32_t bits = a.width == Width::Bit ? 1 : a.width == Width::Word ? 16 : 32;
    if (a.width != Width::Bit && a.index % 8 != 0) {
      *why = "the start of a W or DW view must be a multiple of 8";
      return false;
    }
    last = uint64_t(a.index) + uint64_t(bits) * count - 1;
  } else if (a.area == Area::RC && a.width == Width::DWord) {
    // DRC names a 32-bit counter (C200..C255) or, below C200, a pair of 16-bit counters.
    if (a.index < kFirst32BitCounter) {
      last = uint64_t(a.index) + 2ull * count - 1;
      if (last >= kFirst32BitCounter) {
        *why = "a 16-bit counter pair cannot run into the 32-bit counters C200..C255";
        return false;
      }
    } else {
      last = uint64_t(a.index) + count - 1;
    }
  } else if (a.area == Area::RC) {
    last = uint64_t(a.index) + count - 1;
    if (a.index < kFirst32BitCounter && last >= kFirst32BitCounter && count > 1) {
      *why = "a block of 16-bit counter values cannot run into the 32-bit counters C200..C255";
      return false;
    }
  } else {
    last = uint64_t(a.index) + (a.width == Width::DWord ? 2ull : 1ull) * count - 1;
  }
  if (last >= size) {
    *why = std::string("out of range: ") + area_name(a.area) + " has elements 0.." +
           std::to_string(size - 1);
    return false;
  }
  return true;
}

}  // namespace

bool try_parse_address(std::string_view text, Address* out, std::string* why) {
  std::string_view s = text;
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  if (s.empty()) {
    *why = "empty address";
    return false;
  }
  for (const auto& p : kPrefixes) {
    if (!starts_with_ci(s, p.text)) continue;
    std::string_view digits = s.substr(std::char_traits<char>::length(p.text));
    if (digits.empty() || !std::isdigit(static_cast<unsigned char>(digits.front()))) continue;
    uint64_t n = 0;
    for (char ch : digits) {
      if (!std::isdigit(static_cast<unsigned char>(ch))) {
        *why = "'" + std::string(text) + "': unexpected character '" + ch + "' in the number";
        return false;
      }
      n = n * 10 + uint64_t(ch - '0');
      if (n > 0xFFFFFFFFull) {
        *why = "'" + std::string(text) + "': number too large";
        return false;
      }
    }
    Address a{p.area, p.width, static_cast<uint32_t>(n)};
    std::string reason;
    if (!span_ok(a, 1, &reason)) {
      *why = "'" + std::string(text) + "': " + reason;
      return false;
    }
    *out = a;
    return true;
  }
  *why = "'" + std::string(text) +
         "': unknown prefix (expected X, Y, M, S, T, C, RT, RC, R, D, F, a W/DW view such as "
         "WX8 or DWM0, or a 32-bit register such as DR0, DD0, DF0, DRT0, DRC200)";
  return false;
}

Address parse_address(std::string_view text) {
  Address a;
  std::string why;
  if (!try_parse_address(text, &a, &why)) throw Error("bad address " + why);
  return a;
}

static std::string prefix_of(const Address& a) {
  std::string p;
  if (is_discrete(a.area)) {
    if (a.width == Width::Word) p = "W";
    if (a.width == Width::DWord) p = "DW";
  } else if (a.width == Width::DWord) {
    p = "D";  // DR, DD, DF, DRT, DRC
  }
  return p + area_name(a.area);
}

std::string format_address(const Address& a) { return prefix_of(a) + std::to_string(a.index); }

std::string format_fatek_address(const Address& a) {
  // R, D and F carry 5 digits; everything else 4 (spec 1.7).
  const bool five = a.area == Area::R || a.area == Area::D || a.area == Area::F;
  char buf[16];
  std::snprintf(buf, sizeof buf, five ? "%05u" : "%04u", a.index);
  return prefix_of(a) + buf;
}

Address offset_address(const Address& a, uint32_t n) {
  std::string why;
  if (!span_ok(a, n + 1, &why)) throw Error("address " + format_address(a) + " + " +
                                            std::to_string(n) + ": " + why);
  Address r = a;
  r.index += n * element_stride(a);
  return r;
}

uint32_t encode_element(const Address& a, int64_t v) {
  int64_t lo = 0, hi = 1;
  if (a.width == Width::Word) lo = -32768, hi = 65535;
  if (a.width == Width::DWord) lo = -2147483648ll, hi = 4294967295ll;
  if (v < lo || v > hi)
    throw Error(format_address(a) + ": value " + std::to_string(v) + " out of range " + std::to_string(lo) + ".." +
                std::to_string(hi));
  if (a.width == Width::Word) return static_cast<uint16_t>(v);  // two's complement for negatives
  return static_cast<uint32_t>(v);
}

void check_span(const Address& a, uint32_t count) {
  std::string why;
  if (count == 0) throw Error("address " + format_address(a) + ": count must be at least 1");
  if (!span_ok(a, count, &why))
    throw Error("address " + format_address(a) + " x " + std::to_string(count) + ": " + why);
}

}  // namespace plc_cell
