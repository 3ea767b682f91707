#pragma once
// The axes' status in the PLC's memory (docs/motion.md "Status"): position DR4088,
// frequency DR4080, pulses left DR4072, ready M1992+n, last step finished M1996+n,
// and the pins; a ladder write of DR4088 on an idle axis sets its position.
#include <cstdint>

#include "plc_cell/motion/axis_state.h"

namespace plc_cell {

class Memory;

namespace motion {

class AxisWiring;

constexpr uint32_t kDecelRelay = 1991;     // M1991: stop/pause with deceleration (FUN140/142/147/148)
constexpr uint32_t kReadyRelay = 1992;     // M1992+n: axis ready
constexpr uint32_t kLastStepRelay = 1996;  // M1996+n: last step finished
constexpr uint32_t kDynamicReg = 4056;     // low byte 5AH: SPD registers followed during the output
constexpr uint32_t kErrReg = 4060, kStepReg = 4064, kRemainReg = 4072, kFreqReg = 4080, kPosReg = 4088;

class StatusRegisters {
 public:
  StatusRegisters(Memory& mem, AxisStates& axes, const AxisWiring& wiring) : mem_(mem), axes_(axes), wiring_(wiring) {}

  void write(uint64_t t);
  // A ladder write of DR4088 on an idle axis sets its position (homing by ladder).
  void adopt_ladder_positions();

 private:
  Memory& mem_;
  AxisStates& axes_;
  const AxisWiring& wiring_;
};

}  // namespace motion
}  // namespace plc_cell
