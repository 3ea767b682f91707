#pragma once
// A condition of a scenario: comparisons joined by "and", each "PROBE OP VALUE [+- TOL]".
//   "Y0"                       Y0 is ON (a bare name means == 1, "not Y0" means == 0)
//   "R0 >= 3 and conveyor_run" both
//   "temperature.oven_temp == 200 C +- 1.5"
//   "axis.slide.state == idle"  an axis state is compared by its word
// A temperature may carry its unit (C); a bit compares with on/off, true/false, 1/0.
// Either side may be a sum of names and numbers, each + or - a word of its own: the line's
// balance "infeed.parts_in == test.passed + test.rejected + robot.parts" compares the sum of
// readings (no units, no axis state; docs/testing-your-cell.md, "Sums").
#include <functional>
#include <string>
#include <vector>

#include "plc_cell/scenario/probe.h"

namespace plc_cell {
namespace scenario {

struct Comparison {
  enum class Op { Eq, Ne, Lt, Le, Gt, Ge };
  struct Term {
    int sign;  // +1 or -1
    Probe probe;
  };
  Probe probe;
  // A sum: probe + each term (those of the right side with their sign turned) OP value.
  std::vector<Term> more;
  Op op = Op::Eq;
  double value = 0;
  std::string word;      // an axis state's word instead of a number
  double tolerance = 0;  // == and != within +- tolerance
  std::string text;      // as written, for reports

  bool holds(const Reading& r) const;  // a comparison of one probe (more is empty)
  // Any comparison; read gives one probe's reading.
  bool holds(const std::function<Reading(const Probe&)>& read) const;
  // Every probe it reads: probe, then those of more.
  std::vector<const Probe*> probes() const;
};

struct Condition {
  std::vector<Comparison> all;  // every one must hold
  std::string text;             // as written

  bool empty() const { return all.empty(); }
};

// Throws plc_cell::Error saying what is wrong and where in the text.
// naming: a line's names (CELL.NAME) or a lone cell's.
Condition parse_condition(const std::string& text, Naming naming = Naming::Cell);
// A tolerance from the step (`tolerance: 0.5`) for the comparisons that have none.
void apply_tolerance(Condition& c, double tolerance);

}  // namespace scenario
}  // namespace plc_cell
