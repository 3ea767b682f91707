#include "plc_cell/hsc/count_decoder.h"

namespace plc_cell {
namespace hsc {

void CountDecoder::weights(const Window& w, std::array<int, 4>* first, std::array<int, 4>* seq) const {
  DecodeState s = state_;
  const int n = span();
  for (int i = 1; i <= n; ++i) (i <= 4 ? (*first)[i - 1] : (*seq)[i - 5]) = decode_delta(mode_, decoding_, &s, w[i - 1], w[i]);
  if (n == 4) *seq = *first;
}

int64_t CountDecoder::sum(const std::array<int, 4>& first, const std::array<int, 4>& seq, int64_t k) {
  int64_t d = 0, n = 0;
  for (int i = 0; i < k && i < 4; ++i) d += first[i];
  if (k > 4) {
    for (int i = 0; i < 4; ++i) n += seq[i];
    d += ((k - 4) / 4) * n;
    for (int i = 0; i < (k - 4) % 4; ++i) d += seq[i];
  }
  return d;
}

void CountDecoder::skip(const Window& w, int64_t k) {
  if (!has_memory() || k <= 0) return;
  const int64_t steps = k <= 8 ? k : 4 + (k - 4) % 4;
  for (int64_t i = 1; i <= steps; ++i) decode_delta(mode_, decoding_, &state_, w[i - 1], w[i]);
}

}  // namespace hsc
}  // namespace plc_cell
