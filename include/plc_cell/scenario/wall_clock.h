#pragma once
// The rules of a scenario run in wall-clock time on a PLC over a link
// (docs/testing-on-hardware.md): what the target cannot do is refused at file:line before
// anything is written, a time window tighter than the target's resolution is refused or,
// within --tolerance, widened, and what a case will write and force is listed before it
// runs (the first line of a run, --dry-run) and read before it starts (restore.h).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/core/error.h"
#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace scenario {

struct WallClockRules {
  std::string target;        // how a refusal names it: "FATEK 127.0.0.1:500 station 1"
  std::string cannot_force;  // the link's reason; "" = it locks points
  // Time windows are checked against it; nullopt (--dry-run, not connected): not checked.
  std::optional<uint64_t> resolution_us;
  uint64_t tolerance_us = 0;  // --tolerance: how much a window may be widened
};

// A line of a report at a step: "FILE:LINE: TEXT".
struct StepNote {
  std::string file;
  int line = 0;
  std::string text;
  std::string to_string() const { return file + ":" + std::to_string(line) + ": " + text; }
};

struct Preflight {
  std::vector<Diagnostic> errors;  // the refusals, at file:line
  std::vector<StepNote> widened;   // "within 0.000 s widened to 3.100 ms (--tolerance 5.000 ms)"
  Case adjusted;                   // c with its windows widened
};

// The steps and properties of c against the rules. Names are resolved against config (an
// unknown name is check_case's to report).
Preflight wall_clock_preflight(const Case& c, const WallClockRules& rules, const CellConfig& config);

// The config a probe's cell resolves names in: a lone cell's for every probe, or in a line
// (docs/lines.md) the config of the cell a name starts with; nullptr for no such cell (the
// target's check reports it).
using ConfigOf = std::function<const CellConfig*(const std::string& cell)>;
// The same on a line: each name resolved in its cell, each label CELL.LABEL.
Preflight wall_clock_preflight(const Case& c, const WallClockRules& rules, const ConfigOf& config_of);

// A point a case writes or forces: what is read before it starts and put back after.
struct TouchedPoint {
  Address address;
  std::string label;  // "part_present (X3)"
  bool held = false;  // forced by the case (a force, or a set of an input)
};

// In the order the case first touches them. Throws nothing: a name that does not resolve
// is left out (check_case reports it).
std::vector<TouchedPoint> touched_points(const Case& c, const CellConfig& config);
// In a line: only the points of the cell named cell ("robot" of "robot.X3"), resolved in its
// config and labelled as the cell labels them; "" is a lone cell's (its names have no cell).
std::vector<TouchedPoint> touched_points(const Case& c, const CellConfig& config, const std::string& cell);

// Every write and force of c, one line each at its step ("force part_present (X3) ON
// (held)", "write R100 = 5"), for --dry-run.
std::vector<StepNote> planned_actions(const Case& c, const CellConfig& config);

// Whether a, as config resolves it, is an input terminal (a set of it forces it).
bool is_input(const Address& a);

}  // namespace scenario
}  // namespace plc_cell
