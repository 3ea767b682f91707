#pragma once
// plc_cell explore: random runs of the declared inputs against the file's properties, in
// virtual time, each on a fresh cell; the first violation shrunk to a minimal run
// (docs/testing-your-cell.md, "Exploring").
#include <cstdint>
#include <functional>
#include <string>

#include "plc_cell/explore/input_run.h"
#include "plc_cell/scenario/runner.h"

namespace plc_cell {
namespace explore {

struct Outcome {
  bool found = false;
  uint64_t runs = 0;         // random runs made
  uint64_t virtual_us = 0;   // their virtual time
  uint64_t found_in_run = 0; // 1, 2, ...
  InputRun original;         // the run that violated, up to its violation
  InputRun shrunk;
  uint64_t shrink_runs = 0;  // the runs the shrinker made
  std::string failure;       // the shrunk run's failure, as plc_cell test reports it
};

// Runs one InputRun on a fresh cell of sc; the case's result.
using Runner = std::function<scenario::CaseResult(const InputRun&)>;

// What must stay the same while shrinking: the property (its file:line) or the fault.
std::string signature(const std::string& failure);

// Makes the run smaller while runner still fails it the same way: fewer changes, shorter
// spans between them, values nearer their domain's low end, the run ending at the
// violation; the times stay on the scan grid of period_us. At most max_runs runs; *runs
// counts them.
InputRun shrink(const scenario::ExploreSpec& spec, InputRun run, const Runner& runner, uint64_t period_us,
                uint64_t max_runs, uint64_t* runs, std::string* failure);

// The shrinker's runs at most: enough for runs of a few hundred changes.
constexpr uint64_t kMaxShrinkRuns = 2000;

// The seed of run n (0, 1, ...) of an exploration: from the file's seed and the run's number.
inline uint64_t run_seed(const scenario::ExploreSpec& spec, uint64_t n) { return spec.seed * 1000003 + n; }

// Random runs from spec.seed until spec.budget_us of virtual time; the first that fails is
// shrunk. period_us: the cell's scan period.
Outcome explore(const scenario::ExploreSpec& spec, uint64_t period_us, const Runner& runner);

}  // namespace explore
}  // namespace plc_cell
