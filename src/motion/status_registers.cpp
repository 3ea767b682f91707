// The axes' status registers and relays, written at every scan and event instant.
#include "plc_cell/motion/status_registers.h"

#include <cmath>

#include "plc_cell/core/memory.h"
#include "plc_cell/motion/axis_wiring.h"

namespace plc_cell {
namespace motion {

bool StatusRegisters::unchanged() const {
  for (int n = 0; n < kAxes; ++n)
    if (axes_[n].axis.moving() || !(at_rest(axes_[n]) == written_[n])) return false;
  return block_.holds(mem_);
}

void StatusRegisters::write(uint64_t t) {
  wiring_.write_pins(t);
  if (unchanged()) return;
  bool moving = false;
  // Through one pointer, as this runs twice in every scan: Memory::set_reg would find the
  // area's storage again for each of the 24 registers.
  uint16_t* const r = mem_.words(Area::R);
  const auto put32 = [r](uint32_t reg, int64_t v) {
    r[reg] = static_cast<uint16_t>(uint64_t(v) & 0xFFFF);
    r[reg + 1] = static_cast<uint16_t>((uint64_t(v) >> 16) & 0xFFFF);
  };
  for (int n = 0; n < kAxes; ++n) {
    AxisState& a = axes_[n];
    // An idle axis (most of them, most scans) has its values at hand: no profile to
    // evaluate, the frequency 0, the rest of its last move.
    const bool m = a.axis.moving();
    moving = moving || m;
    a.written_pos = static_cast<int32_t>(m ? a.axis.position(t) : a.axis.idle_position());
    put32(kPosReg + 2 * n, a.written_pos);
    put32(kFreqReg + 2 * n, m ? std::llround(a.axis.frequency(t)) : 0);
    put32(kRemainReg + 2 * n, m ? a.axis.remaining(t) : a.rest);
    mem_.set_bit(Area::M, kReadyRelay + n, a.owner == kFree);
    mem_.set_bit(Area::M, kLastStepRelay + n, a.finished);
  }
  if (moving) {
    block_.forget();  // a moving axis's values change with t
    return;
  }
  for (int n = 0; n < kAxes; ++n) written_[n] = at_rest(axes_[n]);
  block_.take(mem_);
}

bool StatusRegisters::adopt_ladder_positions() {
  const uint16_t* const pos = mem_.words(Area::R) + kPosReg;
  bool adopted = false;
  for (int n = 0; n < kAxes; ++n) {
    AxisState& a = axes_[n];
    const int64_t reg = static_cast<int32_t>(uint32_t(pos[2 * n]) | (uint32_t(pos[2 * n + 1]) << 16));
    if (reg != a.written_pos && !a.axis.moving()) {
      a.axis.set_position(reg);
      adopted = true;
    }
  }
  return adopted;
}

}  // namespace motion
}  // namespace plc_cell
