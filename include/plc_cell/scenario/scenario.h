#pragma once
// A scenario file, parsed: the cell (or the line of cells) it runs, and test cases, each a list of steps on the
// virtual timeline (docs/testing-your-cell.md). Parameterised cases are already expanded:
// one Case per row, its name carrying the row ("count[n=3]").
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "plc_cell/core/error.h"
#include "plc_cell/scenario/condition.h"

namespace plc_cell {
namespace scenario {

// A value a step sets: a number (a bit's on/off is 1/0), or for a probe of a family that
// takes stimuli a quantity in one of its units (config/probe_facet.h: 5 V, 12 mA, 200 C,
// 8.138 mV, 110 ohm), then number is in the family's unit (10 kohm: 10000, unit "ohm").
struct Value {
  double number = 0;
  bool has_unit = false;
  std::string unit;
  std::string text;  // as written
};

struct Assignment {
  Probe target;
  Value value;             // set, write, force (1/0); ramp: the end value
  Value from;              // ramp: the start value
  uint64_t duration_us = 0;  // pulse: its width; ramp: its length
  int line = 0;
};

// One entry of expect_sequence: its condition must become true (false at the scan before)
// at or after the previous entry's match, within [min_us, max_us] of that match.
struct SequenceEntry {
  Condition cond;
  uint64_t min_us = 0;
  uint64_t max_us = UINT64_MAX;
  int line = 0;
};

struct Step {
  enum class Kind {
    Wait,      // only at: / after:
    Set,       // input terminals and stimuli held; other addresses written
    Write,     // one memory write, as a client's
    Force,
    Release,   // assignments name the points; none: all
    Simulate,  // the inputs go back to the cell's simulation; none: all
    Pulse,     // on now, off after duration_us
    Ramp,      // from -> value linearly over duration_us, applied before every scan
    Expect,
    WaitUntil,
    Sequence,
  };
  Kind kind = Kind::Wait;
  std::string key;  // the action's key as written ("expect", "wait_until", ...)
  std::string file;
  int line = 0;
  // When: at an absolute time of the case, or after a span from now; both 0: now.
  bool has_at = false;
  uint64_t at_us = 0;
  uint64_t after_us = 0;

  std::vector<Assignment> assignments;

  Condition cond;                 // Expect, WaitUntil
  uint64_t stays_us = 0;          // Expect: holds at every scan for this long
  bool has_window = false;        // Expect: first holds within [window_min_us, window_max_us]
  uint64_t window_min_us = 0, window_max_us = 0;
  uint64_t timeout_us = 0;        // WaitUntil, Sequence
  std::vector<SequenceEntry> sequence;
};

// A property of the file: checked after every scan of every case. "never: C" is violated
// while C holds; "always: A -> B" while A holds and B does not ("always: B": while B does
// not). A violation fails the case once it has lasted longer than within_us (0: at once).
struct Property {
  bool never = false;
  Condition when;  // always: the antecedent (empty: every scan)
  Condition cond;  // never: what must not hold; always: what must hold
  uint64_t within_us = 0;
  std::string text;  // "never: Y0 and Y1", as written
  std::string file;
  int line = 0;

  bool violated(const std::function<bool(const Condition&)>& holds) const;
};

// What `plc_cell explore` may drive (docs/testing-your-cell.md): one input with its values
// and how long each value is held, at least hold_min_us (the shortest pulse).
struct InputDomain {
  Probe probe;
  double lo = 0, hi = 1;  // a bit: 0..1
  uint64_t hold_min_us = 0, hold_max_us = 0;
  int line = 0;
};

struct ExploreSpec {
  std::vector<InputDomain> inputs;
  uint64_t run_us = 0;     // the length of one random run
  uint64_t budget_us = 0;  // virtual time over all runs
  uint64_t seed = 1;
  int line = 0;  // 0: the file has no explore section
};

struct Case {
  std::string name;
  std::string file;
  int line = 0;
  std::vector<Step> steps;  // the file's setup, the case's setup, then its steps
  std::vector<Property> properties;  // the file's
};

// Whether the file may run on a real PLC (`plc_cell test --target`, the wall-clock ROS
// target; docs/testing-on-hardware.md): `hardware: true`, a list of the targets allowed,
// or {targets: [...], require_run: false}. A file without it runs in virtual time only.
struct HardwarePermission {
  bool allowed = false;
  std::vector<std::string> targets;  // empty: any; else patterns, '*' matching any text
  bool require_run = true;           // the PLC must be in RUN
  int line = 0;                      // the key's line; 0: the file has none
  // Why the file does not allow target (as --target gives it), or "".
  std::string refuses(const std::string& target) const;
};

struct Scenario {
  std::string file;
  std::string cell;     // the cell YAML, resolved against the scenario's folder
  std::string program;  // overrides the cell's program; empty: the cell's
  // Or a line of cells (docs/lines.md): its line file, resolved the same way; cell and
  // program are then empty, and every name of the file is CELL.NAME (Naming::Line).
  std::string line;
  SourceLocation cell_at, program_at, line_at;  // where the file names them
  std::vector<Case> cases;
  std::vector<Property> properties;
  ExploreSpec explore;
  HardwarePermission hardware;
};

constexpr uint64_t kDefaultTimeoutUs = 10000000;  // wait_until and expect_sequence: 10 s

}  // namespace scenario
}  // namespace plc_cell
