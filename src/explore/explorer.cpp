#include "plc_cell/explore/explorer.h"

namespace plc_cell {
namespace explore {

Outcome explore(const scenario::ExploreSpec& spec, uint64_t period_us, const Runner& runner) {
  Outcome o;
  while (o.virtual_us < spec.budget_us) {
    const InputRun run = random_run(spec, run_seed(spec, o.runs), period_us);
    ++o.runs;
    const scenario::CaseResult r = runner(run);
    o.virtual_us += r.virtual_us;
    if (r.passed) continue;
    o.found = true;
    o.found_in_run = o.runs;
    o.original = run;
    o.original.end_us = r.virtual_us;
    o.shrunk = shrink(spec, run, runner, period_us, kMaxShrinkRuns, &o.shrink_runs, &o.failure);
    break;
  }
  return o;
}

}  // namespace explore
}  // namespace plc_cell
