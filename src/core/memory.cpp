#include "plc_cell/core/memory.h"

#include <algorithm>

namespace plc_cell {

Memory::Memory() {
  for (int a = 0; a <= static_cast<int>(Area::C); ++a)
    bits_[a].assign(area_size(static_cast<Area>(a)), 0);
  for (int a = kFirstWordArea; a < kAreaCount; ++a)
    words_[a - kFirstWordArea].assign(word_count(static_cast<Area>(a)), 0);
}

void Memory::set_disabled(Area a, uint32_t i, bool d) {
  uint8_t& c = bits_[idx(a)][i];
  const uint8_t before = c;
  c = d ? (c | kBitDisabled) : (c & ~kBitDisabled);
  if (c != before) ++disabled_gen_;
}

std::vector<Address> Memory::disabled_points() const {
  std::vector<Address> out;
  for (int ai = 0; ai < kAreaCount; ++ai) {
    const Area a = static_cast<Area>(ai);
    if (!is_discrete(a)) continue;
    const auto& b = bits_[idx(a)];
    for (uint32_t i = 0; i < b.size(); ++i)
      if (b[i] & kBitDisabled) out.push_back(Address{a, Width::Bit, i});
  }
  return out;
}

void Memory::force_bit(Area a, uint32_t i, bool v) {
  uint8_t& c = bits_[idx(a)][i];
  c = (c & kBitDisabled) | (v ? kBitState : 0);
}

uint32_t Memory::read(const Address& a) const {
  if (is_discrete(a.area)) {
    const uint8_t* b = bits(a.area) + a.index;
    const int n = a.width == Width::Bit ? 1 : a.width == Width::Word ? 16 : 32;
    uint32_t v = 0;
    for (int k = 0; k < n; ++k) v |= uint32_t(b[k] & kBitState) << k;
    return v;
  }
  const uint16_t* w = words(a.area) + word_index(a.area, a.index);
  if (a.width == Width::DWord) return uint32_t(w[0]) | (uint32_t(w[1]) << 16);
  return w[0];
}

void Memory::write(const Address& a, uint32_t v) {
  if (is_discrete(a.area)) {
    const int n = a.width == Width::Bit ? 1 : a.width == Width::Word ? 16 : 32;
    for (int k = 0; k < n; ++k) set_bit(a.area, a.index + k, (v >> k) & 1u);
    return;
  }
  uint16_t* w = words(a.area) + word_index(a.area, a.index);
  w[0] = static_cast<uint16_t>(v);
  if (a.width == Width::DWord) w[1] = static_cast<uint16_t>(v >> 16);
}

void Memory::clear_non_retentive(const std::vector<AreaRange>& retentive) {
  for (int ai = 0; ai < kAreaCount; ++ai) {
    const Area a = static_cast<Area>(ai);
    const uint32_t n = area_size(a);
    std::vector<uint8_t> keep(n, 0);  // bytes: read once per element of every area
    for (const auto& r : retentive)
      if (r.area == a)
        for (uint32_t i = r.first; i <= std::min(r.last, n - 1); ++i) keep[i] = true;
    for (uint32_t i = 0; i < n; ++i) {
      if (keep[i]) continue;
      if (is_discrete(a)) {
        bits_[ai][i] &= kBitDisabled;
      } else {
        uint16_t* w = words(a) + word_index(a, i);
        w[0] = 0;
        if (a == Area::RC && i >= kFirst32BitCounter) w[1] = 0;
      }
    }
  }
}

void Memory::clear_all() {
  ++disabled_gen_;
  for (auto& b : bits_) std::fill(b.begin(), b.end(), 0);
  for (auto& w : words_) std::fill(w.begin(), w.end(), 0);
}

}  // namespace plc_cell
