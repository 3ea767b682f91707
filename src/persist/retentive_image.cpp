#include "plc_cell/persist/retentive_image.h"

#include <cstring>

#include "plc_cell/core/area.h"
#include "plc_cell/core/error.h"

namespace plc_cell {
namespace persist {
namespace {

uint32_t get32(const uint8_t* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }

// Register ranges store words; RC n >= 200 takes two (Memory::word_index).
uint32_t first_word(Area a, uint32_t i) { return Memory::word_index(a, i); }
uint32_t end_word(Area a, uint32_t last) { return Memory::word_index(a, last) + (a == Area::RC && last >= kFirst32BitCounter ? 2 : 1); }

bool inside(const std::vector<AreaRange>& rs, Area a, uint32_t i) {
  for (const auto& r : rs)
    if (r.area == a && i >= r.first && i <= r.last) return true;
  return false;
}

}  // namespace

// Runs every scan under the PLC lock: sized once, then filled with plain copies.
void encode_retentive(const std::vector<AreaRange>& ranges, const Memory& m, std::vector<uint8_t>* out) {
  size_t n = 0;
  for (const auto& r : ranges)
    n += 9 + (is_discrete(r.area) ? r.last - r.first + 1 : 2 * size_t(end_word(r.area, r.last) - first_word(r.area, r.first)));
  out->resize(n);
  uint8_t* p = out->data();
  for (const auto& r : ranges) {
    *p++ = uint8_t(r.area);
    for (int k = 0; k < 4; ++k) *p++ = uint8_t(r.first >> (8 * k));
    for (int k = 0; k < 4; ++k) *p++ = uint8_t(r.last >> (8 * k));
    if (is_discrete(r.area)) {
      const uint8_t* b = m.bits(r.area);
      for (uint32_t i = r.first; i <= r.last; ++i) *p++ = b[i] & kBitState;
    } else {
      const uint16_t* w = m.words(r.area);
      const uint32_t w0 = first_word(r.area, r.first), w1 = end_word(r.area, r.last);
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
      std::memcpy(p, w + w0, 2 * size_t(w1 - w0));  // the stored form is little-endian
      p += 2 * size_t(w1 - w0);
#else
      for (uint32_t i = w0; i < w1; ++i) {
        *p++ = uint8_t(w[i]);
        *p++ = uint8_t(w[i] >> 8);
      }
#endif
    }
  }
}

size_t decode_retentive(const std::vector<uint8_t>& image, const std::vector<AreaRange>& ranges, Memory* m) {
  size_t pos = 0, restored = 0;
  while (pos < image.size()) {
    if (image.size() - pos < 9) throw Error("retentive image: truncated range header");
    const uint8_t a8 = image[pos];
    const uint32_t first = get32(&image[pos + 1]), last = get32(&image[pos + 5]);
    pos += 9;
    if (a8 >= kAreaCount) throw Error("retentive image: bad area code");
    const Area a = Area(a8);
    if (first > last || last >= area_size(a)) throw Error("retentive image: bad range");
    if (is_discrete(a)) {
      const size_t n = last - first + 1;
      if (image.size() - pos < n) throw Error("retentive image: truncated discretes");
      for (uint32_t i = first; i <= last; ++i, ++pos)
        if (inside(ranges, a, i)) {
          m->force_bit(a, i, image[pos] & kBitState);  // keeps a point's force flag as it is
          ++restored;
        }
    } else {
      const size_t n = 2 * size_t(end_word(a, last) - first_word(a, first));
      if (image.size() - pos < n) throw Error("retentive image: truncated registers");
      uint16_t* w = m->words(a);
      for (uint32_t i = first; i <= last; ++i) {
        const uint32_t k0 = first_word(a, i), k1 = end_word(a, i);
        const bool keep = inside(ranges, a, i);
        for (uint32_t k = k0; k < k1; ++k, pos += 2)
          if (keep) w[k] = uint16_t(image[pos] | image[pos + 1] << 8);
        restored += keep;
      }
    }
  }
  return restored;
}

}  // namespace persist
}  // namespace plc_cell
