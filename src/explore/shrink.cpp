#include <algorithm>
#include <cmath>

#include "plc_cell/explore/explorer.h"

namespace plc_cell {
namespace explore {

std::string signature(const std::string& failure) {
  const auto prop = failure.find(": property ");
  if (prop != std::string::npos) return failure.substr(0, failure.find(" violated", prop));
  const auto fault = failure.find("the PLC stopped on a fault");
  if (fault != std::string::npos) return failure.substr(fault);
  return failure;
}

namespace {

class Shrinker {
 public:
  Shrinker(const scenario::ExploreSpec& spec, const Runner& runner, uint64_t period_us, uint64_t max_runs,
           uint64_t* runs)
      : spec_(spec), runner_(runner), period_(period_us ? period_us : 1), max_runs_(max_runs), runs_(runs) {}

  // Accepts candidate when it keeps to the domains and fails as best does.
  bool try_run(InputRun candidate) {
    std::stable_sort(candidate.changes.begin(), candidate.changes.end(), [](const Change& a, const Change& b) {
      return a.t_us != b.t_us ? a.t_us < b.t_us : a.input < b.input;
    });
    drop_no_ops(spec_, &candidate);
    if (!respects_domains(spec_, candidate) || *runs_ >= max_runs_) return false;
    if (candidate.changes == best_.changes && candidate.end_us >= best_.end_us) return false;
    ++*runs_;
    const scenario::CaseResult r = runner_(candidate);
    if (r.passed || signature(r.failure) != signature_) return false;
    adopt(candidate, r);
    return true;
  }

  void adopt(InputRun run, const scenario::CaseResult& r) {
    run.end_us = r.virtual_us;  // nothing after the violation matters
    run.changes.erase(std::remove_if(run.changes.begin(), run.changes.end(),
                                     [&](const Change& c) { return c.t_us >= run.end_us; }),
                      run.changes.end());
    best_ = run;
    failure_ = r.failure;
    signature_ = signature(r.failure);
  }

  // Fewer changes: chunks of halving sizes, from the end.
  bool remove_changes() {
    bool any = false;
    for (size_t k = std::max<size_t>(best_.changes.size() / 2, 1);; k /= 2) {
      for (size_t i = best_.changes.size(); i > 0;) {
        const size_t from = i >= k ? i - k : 0;
        InputRun c = best_;
        c.changes.erase(c.changes.begin() + long(from), c.changes.begin() + long(i));
        if (try_run(c)) any = true;
        i = std::min(from, best_.changes.size());
      }
      if (k <= 1) break;
    }
    return any;
  }

  // Shorter spans: change i earlier by the span before it, then by halves; with the
  // changes after it (the span before i shrinks) or alone.
  bool shorten_spans() {
    bool any = false;
    for (size_t i = 0; i < best_.changes.size(); ++i) {
      const uint64_t prev = i ? best_.changes[i - 1].t_us : 0;
      bool moved = false;
      for (uint64_t d = best_.changes[i].t_us - prev; d >= period_ && !moved; d /= 2) {
        d -= d % period_;  // on the scan grid
        for (bool alone : {false, true}) {
          InputRun c = best_;
          for (size_t j = i; j < (alone ? i + 1 : c.changes.size()); ++j) c.changes[j].t_us -= d;
          if ((moved = try_run(c))) break;
        }
      }
      any |= moved;
    }
    return any;
  }

  // Simpler values: a register's value as near its low end as still fails (bisection).
  bool simplify_values() {
    bool any = false;
    for (size_t i = 0; i < best_.changes.size(); ++i) {
      double lo = spec_.inputs[best_.changes[i].input].lo;  // the simplest value
      auto with = [&](double v) {
        InputRun c = best_;
        c.changes[i].value = v;
        return try_run(c);
      };
      if (best_.changes[i].value == lo || with(lo)) continue;
      // lo does not fail; the current value does.
      for (double hi = best_.changes[i].value; i < best_.changes.size() && hi - lo > 1;) {
        const double mid = std::floor((lo + hi) / 2);
        if (with(mid)) hi = mid, any = true;
        else lo = mid;
      }
    }
    return any;
  }

  InputRun best_;
  std::string failure_, signature_;

 private:
  const scenario::ExploreSpec& spec_;
  const Runner& runner_;
  const uint64_t period_;
  const uint64_t max_runs_;
  uint64_t* runs_;
};

}  // namespace

InputRun shrink(const scenario::ExploreSpec& spec, InputRun run, const Runner& runner, uint64_t period_us,
                uint64_t max_runs, uint64_t* runs, std::string* failure) {
  Shrinker s(spec, runner, period_us, max_runs, runs);
  ++*runs;
  const scenario::CaseResult first = runner(run);
  if (first.passed) return run;
  s.adopt(run, first);
  // Each pass until none makes the run smaller (or the runs are spent).
  for (bool smaller = true; smaller && *runs < max_runs;)
    smaller = s.remove_changes() | s.shorten_spans() | s.simplify_values();
  if (failure) *failure = s.failure_;
  return s.best_;
}

}  // namespace explore
}  // namespace plc_cell
