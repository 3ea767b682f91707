#pragma once
// Device memory of one FBs-PLC. Not thread-safe: the Plc facade serialises access.
#include <array>
#include <cstdint>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/area.h"

namespace plc_cell {

// A discrete cell holds its state in bit 0 and the DISABLE (force) flag in bit 1:
// one byte load answers a contact, and a coil checks the flag in the same byte.
constexpr uint8_t kBitState = 0x01;
constexpr uint8_t kBitDisabled = 0x02;

struct AreaRange {
  Area area;
  uint32_t first;
  uint32_t last;  // inclusive
};

class Memory {
 public:
  Memory();

  // Discretes. set_bit leaves a disabled (forced) point unchanged, as the PLC does.
  bool bit(Area a, uint32_t i) const { return bits_[idx(a)][i] & kBitState; }
  void set_bit(Area a, uint32_t i, bool v) {
    uint8_t& c = bits_[idx(a)][i];
    if (!(c & kBitDisabled)) c = v ? kBitState : 0;
  }
  bool disabled(Area a, uint32_t i) const { return bits_[idx(a)][i] & kBitDisabled; }
  void set_disabled(Area a, uint32_t i, bool d);
  // Every discrete whose DISABLE flag is set, in area order. A forced point is invisible in
  // the I/O image (it looks like any other state), so operators need the list itself.
  std::vector<Address> disabled_points() const;
  // Changes whenever a DISABLE flag changes: readers compare it instead of walking memory.
  uint64_t disabled_generation() const { return disabled_gen_; }
  // Sets the state even of a disabled point (FATEK command 42 SET/RESET, forcing).
  void force_bit(Area a, uint32_t i, bool v);

  // Registers by element number (RC n >= 200 is the low word of the 32-bit counter).
  uint16_t reg(Area a, uint32_t i) const { return words_[idx(a) - kFirstWordArea][word_index(a, i)]; }
  void set_reg(Area a, uint32_t i, uint16_t v) { words_[idx(a) - kFirstWordArea][word_index(a, i)] = v; }

  // Any address: Bit -> 0/1, Word -> 16 bits, DWord -> 32 bits. Caller checks ranges.
  uint32_t read(const Address& a) const;
  void write(const Address& a, uint32_t v);

  // Raw storage, for the interpreter's pre-resolved operands.
  uint8_t* bits(Area a) { return bits_[idx(a)].data(); }
  const uint8_t* bits(Area a) const { return bits_[idx(a)].data(); }
  uint16_t* words(Area a) { return words_[idx(a) - kFirstWordArea].data(); }
  const uint16_t* words(Area a) const { return words_[idx(a) - kFirstWordArea].data(); }
  static uint32_t word_index(Area a, uint32_t i) { return a == Area::RC ? rc_word_index(i) : i; }
  static uint32_t word_count(Area a) { return a == Area::RC ? kRcWordCount : area_size(a); }

  // Power-on / RUN initialisation: clears all but the retentive ranges. Disable flags are kept.
  void clear_non_retentive(const std::vector<AreaRange>& retentive);
  void clear_all();

 private:
  static constexpr int kFirstWordArea = static_cast<int>(Area::RT);
  static int idx(Area a) { return static_cast<int>(a); }

  std::array<std::vector<uint8_t>, 6> bits_;
  std::array<std::vector<uint16_t>, 5> words_;
  uint64_t disabled_gen_ = 0;
};

}  // namespace plc_cell
