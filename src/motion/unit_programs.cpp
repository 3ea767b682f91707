// A table run on an axis without a ladder FUN140 (ROS services and actions): the program
// of instance kExternal + axis, whose EN/PAU/ABT are the commands.
#include "plc_cell/motion/positioning.h"

namespace plc_cell {
namespace motion {

namespace {
constexpr uint32_t kExternal = 0x80000000u;  // instance ids of unit-run programs (+ axis)
}  // namespace

bool Positioning::load_table(int ps, const Table& t, std::string* why) {
  if (ps < 0 || ps >= kAxes) return *why = "axis must be 0-3", false;
  const uint32_t id = kExternal + ps;
  if (x_.axes[ps].owner != kFree && x_.axes[ps].owner != id) return *why = "a ladder FUN140 holds the axis", false;
  TableError e;
  if (!check_table(t, &e)) return *why = e.message, false;
  Program& p = programs_[id];
  if (p.phase != Phase::Idle && p.phase != Phase::Done) return *why = "the axis is running a table", false;
  p.external = true;
  p.call.ps = ps;
  p.call.instance = id;
  p.table = t;
  p.step = 0;
  return true;
}

bool Positioning::has_table(int ps) const {
  auto it = programs_.find(kExternal + ps);
  return it != programs_.end() && !it->second.table.steps.empty();
}

bool Positioning::program_running(int ps) const {
  auto it = programs_.find(kExternal + ps);
  if (it == programs_.end()) return false;
  const Phase ph = it->second.phase;
  return ph != Phase::Idle && ph != Phase::Done;
}

bool Positioning::command(int ps, ProgramCommand c, std::string* why) {
  if (ps < 0 || ps >= kAxes) return *why = "axis must be 0-3", false;
  auto it = programs_.find(kExternal + ps);
  if (it == programs_.end() || it->second.table.steps.empty()) return *why = "no table loaded on this axis", false;
  Program& p = it->second;
  const uint64_t now = x_.now_ns;
  advance(p, now);
  switch (c) {
    case ProgramCommand::Start:
      if (x_.axes[ps].owner != kFree && x_.axes[ps].owner != p.call.instance)
        return *why = "a ladder FUN140 holds the axis", false;
      if (program_running(ps)) return *why = "already running", false;
      p.step = 0;  // from the first step
      p.armed = true;
      p.call.en = true;
      p.call.pau = p.call.abt = false;
      fun140(p.call, now / 1000);
      return true;
    case ProgramCommand::Pause:
      p.call.pau = true;
      return true;
    case ProgramCommand::Resume:
      p.call.pau = false;
      return true;
    case ProgramCommand::Abort:
      if (p.phase != Phase::Idle && p.phase != Phase::Done && p.phase != Phase::Stopping)
        stop(p, now, Phase::Idle, /*force_decel=*/true);
      p.call.en = false;
      p.call.pau = false;
      p.step = 0;
      return true;
  }
  return false;
}

}  // namespace motion
}  // namespace plc_cell
