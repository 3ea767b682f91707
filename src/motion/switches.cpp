// Inputs driven by the axis positions: windows (DOG, limits) and periodic pulses (PG0).
#include "plc_cell/motion/switches.h"

#include "plc_cell/core/memory.h"

namespace plc_cell {
namespace motion {

namespace {
int64_t floor_mod(int64_t a, int64_t m) {
  const int64_t r = a % m;
  return r < 0 ? r + m : r;
}
}  // namespace

bool SwitchDef::level(int64_t pos) const {
  if (period > 0) return floor_mod(pos - offset, period) < width;
  return pos >= from && pos <= to;
}

int64_t SwitchDef::next_change(int64_t pos, int dir) const {
  if (period > 0) {
    const int64_t r = floor_mod(pos - offset, period);
    if (dir > 0) return r < width ? pos + (width - r) : pos + (period - r);
    return r < width ? pos - r - 1 : pos - (r - (width - 1));
  }
  if (dir > 0) {
    if (pos < from) return from;
    if (pos <= to) return to + 1;
    return INT64_MIN;
  }
  if (pos > to) return to;
  if (pos >= from) return from - 1;
  return INT64_MIN;
}

bool Switches::input(int x, uint64_t t) const {
  bool driven = false, on = false;
  for (int n = 0; n < kAxes; ++n)
    for (const auto& sw : cfg_.axes[n].switches)
      if (sw.x == x) {
        driven = true;
        on = on || sw.level(axes_[n].axis.position(t));
      }
  return driven ? on : mem_.bit(Area::X, x);
}

void Switches::write(uint64_t t) const {
  for (int n = 0; n < kAxes; ++n)
    for (const auto& sw : cfg_.axes[n].switches) mem_.set_bit(Area::X, sw.x, input(sw.x, t));
}

}  // namespace motion
}  // namespace plc_cell
