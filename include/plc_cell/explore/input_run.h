#pragma once
// One exploration run: the changes it makes to the declared inputs, on the virtual
// timeline, as a scenario case that replays them (docs/testing-your-cell.md, "Exploring").
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace explore {

// After the scan at t_us, input (an index into the explore section's inputs) takes value;
// the next scan sees it. Every input holds its domain's low value from the first scan.
struct Change {
  uint64_t t_us = 0;
  size_t input = 0;
  double value = 0;
  bool operator==(const Change& o) const { return t_us == o.t_us && input == o.input && value == o.value; }
};

struct InputRun {
  std::vector<Change> changes;  // by time, then by input
  uint64_t end_us = 0;          // the run's last scan
};

// A random run of spec.run_us from seed: each input holds each value for a span drawn from
// its hold range (whole scan periods), then changes (a bit toggles; a register takes
// another value of its range). The same seed gives the same run.
InputRun random_run(const scenario::ExploreSpec& spec, uint64_t seed, uint64_t period_us);

// True when every input holds each value at least its shortest hold (the first change too,
// counted from 0) and the changes are in order.
bool respects_domains(const scenario::ExploreSpec& spec, const InputRun& run);

// Drops the changes that set an input to the value it already has.
void drop_no_ops(const scenario::ExploreSpec& spec, InputRun* run);

// The run as a case of the scenario (its properties included) named name.
scenario::Case as_case(const scenario::Scenario& sc, const InputRun& run, const std::string& name);

// "on"/"off" for a bit domain, else the whole number.
std::string value_text(const scenario::InputDomain& d, double v);

}  // namespace explore
}  // namespace plc_cell
