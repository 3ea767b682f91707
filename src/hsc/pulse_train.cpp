#include "plc_cell/hsc/pulse_train.h"

namespace plc_cell {
namespace hsc {

// Rising at delay + k*period, falling width later.
uint64_t PulseTrain::find_next_after(uint64_t t, bool* rising) const {
  asked = t;
  edge = next_edge(t, &edge_rising);
  *rising = edge_rising;
  return edge;
}

uint64_t PulseTrain::next_edge(uint64_t t, bool* rising) const {
  if (t < delay) {
    *rising = true;
    return delay;
  }
  const uint64_t k = (t - delay) / period;
  const uint64_t r = delay + k * period;
  if (r + width > t) {
    *rising = false;
    return r + width;
  }
  *rising = true;
  return r + period;
}

}  // namespace hsc
}  // namespace plc_cell
