#include "plc_cell/recording/image.h"

#include <algorithm>

namespace plc_cell {
namespace recording {

namespace {

constexpr Area kBitAreas[] = {Area::X, Area::Y, Area::M, Area::S, Area::T, Area::C};
constexpr Area kWordAreas[] = {Area::RT, Area::RC, Area::R, Area::D, Area::F};

uint32_t sum_bits() {
  uint32_t n = 0;
  for (Area a : kBitAreas) n += area_size(a);
  return n;
}

uint32_t sum_words() {
  uint32_t n = 0;
  for (Area a : kWordAreas) n += Memory::word_count(a);
  return n;
}

}  // namespace

uint32_t bit_cells() {
  static const uint32_t n = sum_bits();
  return n;
}

uint32_t word_cells() {
  static const uint32_t n = sum_words();
  return n;
}

void capture(const Memory& m, Image* out) {
  out->bits.resize(bit_cells());
  out->words.resize(word_cells());
  uint8_t* b = out->bits.data();
  for (Area a : kBitAreas) b = std::copy_n(m.bits(a), area_size(a), b);
  uint16_t* w = out->words.data();
  for (Area a : kWordAreas) w = std::copy_n(m.words(a), Memory::word_count(a), w);
}

void restore(const Image& img, Memory* m) {
  const uint8_t* b = img.bits.data();
  for (Area a : kBitAreas) {
    std::copy_n(b, area_size(a), m->bits(a));
    b += area_size(a);
  }
  const uint16_t* w = img.words.data();
  for (Area a : kWordAreas) {
    std::copy_n(w, Memory::word_count(a), m->words(a));
    w += Memory::word_count(a);
  }
}

std::string bit_cell_name(uint32_t n) {
  for (Area a : kBitAreas) {
    if (n < area_size(a)) return format_address(Address{a, Width::Bit, n});
    n -= area_size(a);
  }
  return "?";
}

std::string word_cell_name(uint32_t n) {
  for (Area a : kWordAreas) {
    if (n < Memory::word_count(a)) {
      if (a == Area::RC && n >= kFirst32BitCounter) {
        const uint32_t c = kFirst32BitCounter + (n - kFirst32BitCounter) / 2;
        return format_address(Address{a, Width::DWord, c}) + ((n - kFirst32BitCounter) % 2 ? " (high)" : " (low)");
      }
      return format_address(Address{a, Width::Word, n});
    }
    n -= Memory::word_count(a);
  }
  return "?";
}

std::vector<uint32_t> cells_of(const Address& a) {
  check_span(a, 1);
  std::vector<uint32_t> out;
  uint32_t at = 0;
  if (is_discrete(a.area)) {
    for (Area x : kBitAreas) {
      if (x == a.area) break;
      at += area_size(x);
    }
    const uint32_t n = a.width == Width::Bit ? 1 : a.width == Width::Word ? 16 : 32;
    for (uint32_t k = 0; k < n; ++k) out.push_back(at + a.index + k);
    return out;
  }
  at = bit_cells();
  for (Area x : kWordAreas) {
    if (x == a.area) break;
    at += Memory::word_count(x);
  }
  out.push_back(at + Memory::word_index(a.area, a.index));
  if (a.width == Width::DWord) out.push_back(out[0] + 1);
  return out;
}

uint32_t value_of(const Address& a, const std::vector<uint16_t>& v) {
  if (is_discrete(a.area)) {
    uint32_t x = 0;
    for (size_t k = 0; k < v.size(); ++k) x |= uint32_t(v[k] & kBitState) << k;
    return x;
  }
  return v.size() > 1 ? uint32_t(v[0]) | (uint32_t(v[1]) << 16) : v.at(0);
}

std::vector<Address> forced_points(const Image& img) {
  std::vector<Address> out;
  uint32_t at = 0;
  for (Area a : kBitAreas)
    for (uint32_t i = 0; i < area_size(a); ++i, ++at)
      if (img.bits[at] & kBitDisabled) out.push_back(Address{a, Width::Bit, i});
  return out;
}

}  // namespace recording
}  // namespace plc_cell
