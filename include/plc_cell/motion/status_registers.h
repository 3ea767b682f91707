#pragma once
// The axes' status in the PLC's memory (docs/motion.md "Status"): position DR4088,
// frequency DR4080, pulses left DR4072, ready M1992+n, last step finished M1996+n,
// and the pins; a ladder write of DR4088 on an idle axis sets its position.
#include <array>
#include <cstdint>

#include "plc_cell/core/status_block.h"
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

  // Skipped when every axis is at rest as at the last write and the block is untouched
  // (core/status_block.h): the same bytes would be stored.
  void write(uint64_t t);
  // A ladder write of DR4088 on an idle axis sets its position (homing by ladder).
  // True if one did.
  bool adopt_ladder_positions();
  // The block holds what the last write left, and that write was of axes at rest.
  bool holds() const { return block_.holds(mem_); }

 private:
  Memory& mem_;
  AxisStates& axes_;
  const AxisWiring& wiring_;
  // What an axis at rest shows: its registers and relays follow from these alone.
  struct AtRest {
    int64_t position, rest;
    bool free, finished;
    bool operator==(const AtRest& o) const {
      return position == o.position && rest == o.rest && free == o.free && finished == o.finished;
    }
  };
  static AtRest at_rest(const AxisState& a) { return {a.axis.idle_position(), a.rest, a.owner == kFree, a.finished}; }
  // Every axis at rest as at the last write, and the block as written then.
  bool unchanged() const;

  std::array<AtRest, kAxes> written_{};
  StatusBlock<kPosReg + 2 * kAxes - kRemainReg, kLastStepRelay + kAxes - kReadyRelay> block_{Area::R, kRemainReg, Area::M,
                                                                                             kReadyRelay};
};

}  // namespace motion
}  // namespace plc_cell
