#include "plc_cell/persist/retentive_image.h"

#include <cstring>
#include <string>

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

std::vector<StoredRange> parse_retentive(const std::vector<uint8_t>& image) {
  std::vector<StoredRange> out;
  size_t pos = 0;
  while (pos < image.size()) {
    const std::string at = "range " + std::to_string(out.size() + 1) + " at byte " + std::to_string(pos);
    if (image.size() - pos < 9) throw Error("retentive image: " + at + ": truncated range header");
    const uint8_t a8 = image[pos];
    const uint32_t first = get32(&image[pos + 1]), last = get32(&image[pos + 5]);
    pos += 9;
    if (a8 >= kAreaCount) throw Error("retentive image: " + at + ": bad area code " + std::to_string(a8));
    const Area a = Area(a8);
    if (first > last || last >= area_size(a))
      throw Error("retentive image: " + at + ": bad range " + area_name(a) + std::to_string(first) + "-" +
                  area_name(a) + std::to_string(last));
    const size_t n = is_discrete(a) ? size_t(last - first + 1) : 2 * size_t(end_word(a, last) - first_word(a, first));
    if (image.size() - pos < n)
      throw Error("retentive image: " + at + ": " + std::to_string(n) + " bytes of values announced, " +
                  std::to_string(image.size() - pos) + " present");
    out.push_back({{a, first, last}, pos});
    pos += n;
  }
  return out;
}

size_t apply_retentive(const std::vector<uint8_t>& image, const std::vector<StoredRange>& stored,
                       const std::vector<AreaRange>& ranges, Memory* m, std::vector<AreaRange>* restored_ranges) {
  size_t restored = 0;
  for (const auto& s : stored) {
    const Area a = s.range.area;
    size_t pos = s.offset;
    for (uint32_t i = s.range.first; i <= s.range.last; ++i) {
      const bool keep = inside(ranges, a, i);
      if (keep && restored_ranges) {
        // Consecutive restored elements of one area extend the last range.
        auto& rr = *restored_ranges;
        if (!rr.empty() && rr.back().area == a && rr.back().last + 1 == i) rr.back().last = i;
        else rr.push_back({a, i, i});
      }
      if (is_discrete(a)) {
        if (keep) m->force_bit(a, i, image[pos] & kBitState);  // keeps a point's force flag as it is
        ++pos;
      } else {
        uint16_t* w = m->words(a);
        for (uint32_t k = first_word(a, i); k < end_word(a, i); ++k, pos += 2)
          if (keep) w[k] = uint16_t(image[pos] | image[pos + 1] << 8);
      }
      restored += keep;
    }
  }
  return restored;
}

size_t decode_retentive(const std::vector<uint8_t>& image, const std::vector<AreaRange>& ranges, Memory* m) {
  const std::vector<StoredRange> stored = parse_retentive(image);  // throws before any write
  return apply_retentive(image, stored, ranges, m);
}

std::string describe_ranges(const std::vector<AreaRange>& ranges) {
  std::string out;
  for (const auto& r : ranges) {
    if (!out.empty()) out += ",";
    out += area_name(r.area) + std::to_string(r.first);
    if (r.last != r.first) out += "-" + std::string(area_name(r.area)) + std::to_string(r.last);
  }
  return out;
}

}  // namespace persist
}  // namespace plc_cell
