#pragma once
// What a subsystem last wrote into its block of status registers and relays.
//
// A subsystem that shows its state in memory writes it at every scan, and an idle one
// (an axis at rest, no group to interpolate) writes the very same values scan after
// scan. When its own state is the one it last wrote and the memory still holds what it
// wrote, a rewrite would store the same bytes, forced relays included (Memory::set_bit
// leaves a disabled point as it is), so the subsystem may skip it. A write into the
// block by the ladder or a client shows here as a difference, and the next status write
// puts the block back exactly as before.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "plc_cell/core/area.h"
#include "plc_cell/core/memory.h"

namespace plc_cell {

template <uint32_t Words, uint32_t Bits>
class StatusBlock {
 public:
  // Words registers from first_word of words_area (not RC), Bits discretes from first_bit.
  StatusBlock(Area words_area, uint32_t first_word, Area bits_area, uint32_t first_bit)
      : words_area_(words_area), first_word_(first_word), bits_area_(bits_area), first_bit_(first_bit) {}

  // The memory holds what take() saw, and nothing forgot it since.
  bool holds(const Memory& m) const {
    return taken_ && same(m.words(words_area_) + first_word_, words_.data(), sizeof words_) &&
           same(m.bits(bits_area_) + first_bit_, bits_.data(), sizeof bits_);
  }
  void take(const Memory& m) {
    std::memcpy(words_.data(), m.words(words_area_) + first_word_, sizeof words_);
    std::memcpy(bits_.data(), m.bits(bits_area_) + first_bit_, sizeof bits_);
    taken_ = true;
  }
  // The status depends on something not kept here (a move in progress): write it anew.
  void forget() { taken_ = false; }

 private:
  // Eight bytes at a time with no early exit: a few instructions for a block this size,
  // where a call to memcmp costs more than the comparison (it runs twice a scan).
  static bool same(const void* a, const void* b, size_t n) {
    const auto* p = static_cast<const unsigned char*>(a);
    const auto* q = static_cast<const unsigned char*>(b);
    uint64_t diff = 0;
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
      uint64_t x, y;
      std::memcpy(&x, p + i, 8);
      std::memcpy(&y, q + i, 8);
      diff |= x ^ y;
    }
    for (; i < n; ++i) diff |= p[i] ^ q[i];
    return diff == 0;
  }

  Area words_area_;
  uint32_t first_word_;
  Area bits_area_;
  uint32_t first_bit_;
  std::array<uint16_t, Words> words_{};
  std::array<uint8_t, Bits> bits_{};
  bool taken_ = false;
};

}  // namespace plc_cell
