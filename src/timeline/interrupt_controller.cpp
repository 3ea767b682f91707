#include "plc_cell/timeline/interrupt_controller.h"

#include <algorithm>

#include "plc_cell/core/program.h"

namespace plc_cell {
namespace timeline {

InterruptController::InterruptController() {
  for (int s = 0; s < kSourceCount; ++s) priority_[s] = s < kHsc4I ? s + 1 : kSourceCount;
  enabled_.fill(true);
}

// From the program's own labels (a few), not from every source's names: a cell's first scan
// binds, and building 53 sources' label strings there was a quarter of that scan.
void InterruptController::bind(const Program& program) {
  present_ = 0;
  for (auto& l : label_) l.clear();
  for (const auto& [label, at] : program.labels) {
    const int s = source_of_label(label);
    if (s < 0 || at < program.main_end) continue;
    // The new name before the old one(s) when a program has both.
    if (present(s)) {
      const std::vector<std::string> names = source_labels(s);
      if (std::find(names.begin(), names.end(), label) > std::find(names.begin(), names.end(), label_[s])) continue;
    }
    label_[s] = label;
    present_ |= uint64_t(1) << s;
  }
  reset();
}

void InterruptController::reset() {
  pending_.fill(false);
  pending_count_ = 0;
  depth_ = 0;
  failed_ = false;
}

void InterruptController::request(int s) {
  if (!present(s) || !enabled_[s] || failed_) return;
  if (!pending_[s]) {
    pending_[s] = true;  // a second request before it runs is the same request
    ++pending_count_;
  }
}

void InterruptController::raise(int s, const Runner& run) {
  request(s);
  dispatch(run);
}

void InterruptController::dispatch(const Runner& run) {
  while (pending_count_ > 0 && !failed_ && depth_ < kMaxNesting) {
    int best = -1;
    for (int s = 0; s < kSourceCount; ++s)
      if (pending_[s] && (best < 0 || priority_[s] < priority_[best])) best = s;
    // Lower or equal priority waits for the running routine; higher pre-empts it.
    if (depth_ > 0 && priority_[best] >= running_[depth_ - 1]) return;
    pending_[best] = false;
    --pending_count_;
    running_[depth_++] = priority_[best];
    const bool ok = run(best, label_[best]);
    --depth_;
    if (!ok) {
      failed_ = true;
      return;
    }
  }
}

}  // namespace timeline
}  // namespace plc_cell
