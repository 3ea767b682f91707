#pragma once
// Internal: reading a step's operands from memory when it runs, shared by the FUN140
// engine (motion_unit.cpp) and the FUN147 engine (interpolation.cpp).
#include <cstdint>

#include "plc_cell/core/memory.h"
#include "plc_cell/motion/table.h"

namespace plc_cell {
namespace motion {
namespace flow {

constexpr uint64_t kTimeUnitNs = 10000000;  // WAIT/ACT times are in 0.01 s
constexpr int kMaxStepsPerInstant = 1000;   // GOTO loops of empty moves must not hang a scan

// The status word WR+1 of a FUN140 axis or a FUN147 group.
constexpr uint16_t kWrPaused = 1u << 8, kWrWaiting = 1u << 9, kWrEndless = 1u << 10, kWrAct = 1u << 12,
                   kWrErr = 1u << 13, kWrDn = 1u << 14;

inline Area area(Operand::Kind k) { return k == Operand::D ? Area::D : Area::R; }

// A 32-bit operand pair (low word first).
inline int32_t read32(const Memory& m, Operand::Kind k, int32_t i) {
  return static_cast<int32_t>(uint32_t(m.reg(area(k), i)) | (uint32_t(m.reg(area(k), i + 1)) << 16));
}
inline int64_t value32(const Memory& m, const Operand& o) {
  return o.kind == Operand::Const ? o.value : read32(m, o.kind, o.value);
}
// WAIT/ACT time in 0.01 s.
inline uint16_t time16(const Memory& m, const Step& s) {
  return s.time.kind == Operand::Const ? static_cast<uint16_t>(s.time.value) : m.reg(area(s.time.kind), s.time.value);
}
// The WAIT/EXT contact.
inline bool contact(const Memory& m, const Step& s) {
  static const Area areas[] = {Area::X, Area::Y, Area::M, Area::S};
  return m.bit(areas[static_cast<int>(s.contact_area)], s.contact);
}
// The GOTO target of step `step` (NEXT: step + 1); 0 if a GOTO constant or register
// names no step of n.
inline int goto_target(const Memory& m, const Step& s, int step, int n) {
  int target;
  switch (s.goto_kind) {
    case Step::Next: return step + 1;
    case Step::Number: target = s.goto_value; break;
    default: target = static_cast<int16_t>(m.reg(s.goto_kind == Step::R ? Area::R : Area::D, s.goto_value));
  }
  return target < 1 || target > n ? 0 : target;
}

}  // namespace flow
}  // namespace motion
}  // namespace plc_cell
