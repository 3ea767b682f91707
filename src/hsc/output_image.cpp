#include "plc_cell/hsc/output_image.h"

#include <cstring>

#include "plc_cell/core/image_loop.h"

namespace plc_cell {
namespace hsc {

namespace {
constexpr uint64_t kStates = 0x0101010101010101ull;  // kBitState of eight points
uint64_t load8(const uint8_t* p) {
  uint64_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// The whole image: no output of ours (owned 0) differs from its terminal (phys).
PLC_CELL_IMAGE_LOOP bool same_outputs(const uint8_t* __restrict y_bits, const uint8_t* __restrict phys,
                                      const uint8_t* __restrict owned) {
  uint8_t diff = 0;
  for (uint32_t y = 0; y < OutputImage::kOutputs; ++y) diff |= ((y_bits[y] & kBitState) ^ phys[y]) & ~owned[y];
  return diff == 0;
}
}  // namespace

void OutputImage::own(uint32_t y, bool owned) {
  if (y < kOutputs) owned_[y] = owned ? 1 : 0;
}

void OutputImage::changed(uint32_t y, bool v, uint64_t t) {
  phys_[y] = v ? 1 : 0;
  for (auto& f : observers_) f(t, y, v);
  for (const Follower& f : followers_)
    if (f.y == y) f.src->set_rate(t, v ? f.hz : 0);
}

// Vectorised (AVX2 where the CPU has it: core/image_loop.h).
bool OutputImage::unchanged() const { return same_outputs(mem_.bits(Area::Y), phys_.data(), owned_.data()); }

void OutputImage::refresh(uint32_t first, uint32_t n, uint64_t t) {
  const uint32_t end = first + n < kOutputs ? first + n : kOutputs;
  const uint8_t* y_bits = mem_.bits(Area::Y);
  uint32_t y = first;
  while (y < end) {
    // Whole blocks of eight with nothing changed are skipped at once.
    if (y % 8 == 0 && y + 8 <= end) {
      const uint64_t diff = ((load8(y_bits + y) & kStates) ^ load8(phys_.data() + y)) & ~load8(owned_.data() + y);
      if (diff == 0) {
        y += 8;
        continue;
      }
    }
    const uint32_t stop = y % 8 == 0 && y + 8 <= end ? y + 8 : y + 1;
    for (; y < stop; ++y) {
      if (owned_[y]) continue;
      const bool v = y_bits[y] & kBitState;
      if (v != (phys_[y] != 0)) changed(y, v, t);
    }
  }
}

}  // namespace hsc
}  // namespace plc_cell
