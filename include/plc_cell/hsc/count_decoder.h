#pragma once
// A counter's decoding of its counting inputs (count_rule.h, decoding.h) applied to the
// boundaries an analytic source crosses: the weights that let the counter count k
// boundaries, and find the one where CV reaches PV, in O(1).
#include <array>
#include <cstdint>

#include "plc_cell/hsc/count_rule.h"
#include "plc_cell/hsc/decoding.h"

namespace plc_cell {
namespace hsc {

class CountDecoder {
 public:
  static constexpr int kMaxSpan = 8;
  // The counting inputs at the present boundary and the next ones: pins[i], i = 0..span().
  using Window = std::array<Pins, kMaxSpan + 1>;

  CountDecoder() = default;
  CountDecoder(Mode m, Decoding d) : mode_(m), decoding_(d) {}

  void reset() { state_ = DecodeState{}; }
  // One change of the inputs; the decoder sees every change, counting or not (MASK and
  // CLEAR stop the count, not the decoder).
  int step(Pins before, Pins after) { return decode_delta(mode_, decoding_, &state_, before, after); }
  // Only the enhanced decoder has a memory; it can lock out the first boundary alone (the
  // source starts inside "both OFF", entered through the phase it now leaves by), so its
  // weights are taken over two periods. Every other rule repeats from the first.
  int span() const { return decoding_ == Decoding::Enhanced ? kMaxSpan : 4; }
  bool has_memory() const { return decoding_ == Decoding::Enhanced; }
  // CV changes at the next boundaries: first[i] at boundary i+1, seq[i] at boundaries
  // 4k+i+1 for every k >= 1 (they repeat from the fifth on).
  void weights(const Window& w, std::array<int, 4>* first, std::array<int, 4>* seq) const;
  // The net change over k boundaries.
  static int64_t sum(const std::array<int, 4>& first, const std::array<int, 4>& seq, int64_t k);
  // Steps the memory over k boundaries: after the first four it repeats every four, so k
  // boundaries cost at most eight steps.
  void skip(const Window& w, int64_t k);

 private:
  Mode mode_ = Mode::UD;
  Decoding decoding_ = Decoding::Fatek;
  DecodeState state_;
};

}  // namespace hsc
}  // namespace plc_cell
