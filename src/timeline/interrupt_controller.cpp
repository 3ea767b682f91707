#include "plc_cell/timeline/interrupt_controller.h"

#include "plc_cell/core/program.h"

namespace plc_cell {
namespace timeline {

InterruptController::InterruptController() {
  for (int s = 0; s < kSourceCount; ++s) priority_[s] = s < kHsc4I ? s + 1 : kSourceCount;
  enabled_.fill(true);
}

void InterruptController::bind(const Program& program) {
  present_ = 0;
  for (int s = 0; s < kSourceCount; ++s) {
    label_[s].clear();
    for (const auto& l : source_labels(s)) {
      auto it = program.labels.find(l);
      if (it != program.labels.end() && it->second >= program.main_end) {
        label_[s] = l;
        present_ |= uint64_t(1) << s;
        break;
      }
    }
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
