#pragma once
// One FUN140 positioning program: what its instruction sees each scan and where its
// table run stands (docs/motion.md "FUN140"). The Positioning component runs it; the
// Homing component runs its DRVZ steps.
#include <cstdint>

#include "plc_cell/core/address.h"
#include "plc_cell/motion/axis.h"
#include "plc_cell/motion/table.h"

namespace plc_cell {
namespace motion {

// What a FUN140 instruction sees this scan.
struct Fun140Call {
  int ps = 0;
  Address sr{}, wr{};
  bool en = false, pau = false, abt = false;
  uint32_t instance = 0;
};
struct Fun140Outputs {
  bool act = false, err = false, dn = false;
};

enum class Phase { Idle, Moving, Waiting, SpeedWait, Paused, Stopping, Done, Homing };
// DRVZ stages (docs/motion.md "Homing").
enum class Home { Seek, ToLimit, Escape, Creep, Md1Stop, Md1Delay, Md1Back, Clr };

struct HomeState {
  Home stage = Home::Seek;
  uint64_t until = kNever;  // MD1 delay / CLR pulse end
  int pg0_count = 0;
  bool counting = false, dog_seen = false, prev_pg0 = false;
};

struct Program {
  Fun140Call call;
  Table table;
  Phase phase = Phase::Idle;
  Phase after_stop = Phase::Idle;  // what a decelerated stop ends in
  int step = 0;                    // 1-based, the step being run
  uint64_t wait_until = kNever;    // WAIT Time / ACT deadline
  uint64_t act_deadline = kNever;
  bool chain = false;              // inside a DRVC chain: the next start keeps the speed
  double speed_hz = 0;
  int64_t paused_left = 0;         // logical pulses left at a pause / cut (DR4072)
  bool prev_en = false, prev_pau = false, prev_abt = false;
  bool dn = false, err = false;
  bool endless = false;
  HomeState home;
  uint64_t t_cur = 0;              // the instant this program was last brought to
  // Steps that completed at once (nothing to move) at instant empty_at: a GOTO loop of
  // such steps never lets time pass, so it is refused as advance()'s guard refuses it.
  uint64_t empty_at = kNever;
  int empty_steps = 0;
  bool armed = true;               // EN was off since the last start
  bool external = false;           // run by load_table/command, no registers
  bool chain_forward = true;
  double chain_speed = 0;          // speed at the end of the previous DRVC section
  bool move_forward = true;
  int move_delta_sign = 1;

  const Step& current() const { return table.steps[step - 1]; }
};

}  // namespace motion
}  // namespace plc_cell
