#pragma once
// A periodic switch on one of X0-X15 (the cell YAML's simulation pulse): on for width of
// every period from delay. Its edges are computed, never queued, so a train costs one
// event per edge and no memory.
#include <cstdint>

namespace plc_cell {
namespace hsc {

struct PulseTrain {
  int x;
  uint64_t period, width, delay;

  // First edge strictly after t; *rising tells which.
  uint64_t next_after(uint64_t t, bool* rising) const {
    if (t >= asked && t < edge) {  // most scans: no call
      *rising = edge_rising;
      return edge;
    }
    return find_next_after(t, rising);
  }
  uint64_t find_next_after(uint64_t t, bool* rising) const;
  uint64_t next_edge(uint64_t t, bool* rising) const;  // the same, computed
  bool level_at(uint64_t t) const { return t >= delay && (t - delay) % period < width; }

  // The last answer holds for every t in [asked, edge): the scheduler asks at each scan,
  // and most scans fall between two edges, so the division is done once per edge.
  mutable uint64_t asked = 1, edge = 0;
  mutable bool edge_rising = false;
};

}  // namespace hsc
}  // namespace plc_cell
