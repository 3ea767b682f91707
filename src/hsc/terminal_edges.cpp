#include "plc_cell/hsc/terminal_edges.h"

#include <algorithm>
#include <string>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace hsc {

void TerminalEdges::schedule(int x, uint64_t t_ns, bool level) {
  if (x >= 0 && x < 16) simulated_[x] = true;
  Edge e{t_ns, seq_++, x, level};
  e.simulated = true;
  edges_.push(e);
}

void TerminalEdges::mute(int x, bool muted) {
  if (x < 0 || x > 15 || muted_[x] == muted) return;
  muted_[x] = muted;
  if (muted || !simulated_[x]) return;
  ctx_.engine.set_input(x, pins_.raw(x));  // not yet scanned: the simulation's level comes instead
  const auto train = std::find_if(trains_.begin(), trains_.end(), [x](const PulseTrain& t) { return t.x == x; });
  if (train == trains_.end()) {
    edges_.push({ctx_.now(), seq_++, x, sim_raw_[x]});  // through the filter, as the steps' edges
    return;
  }
  // A train's levels are the filter's output already: they act unfiltered, and whatever
  // the filter still holds from outside is void.
  ++pins_[x].gen;
  edges_.push({ctx_.now(), seq_++, x, train->level_at(ctx_.now()), true, pins_[x].gen});
}

void TerminalEdges::add_train(int x, uint64_t period_ns, uint64_t width_ns, uint64_t delay_ns) {
  if (x < 0 || x > 15 || pins_.driven(x)) throw Error("X" + std::to_string(x) + ": no pulse train here");
  simulated_[x] = true;
  if (period_ns == 0 || width_ns == 0) return;  // never on
  if (width_ns >= period_ns) {
    schedule(x, delay_ns, true);  // on for good
    return;
  }
  // The filter, in O(1) for the whole train: it loses ON pulses shorter than its
  // width, bridges OFF gaps shorter than it, and delays the rest by its width.
  const uint64_t w = pins_[x].filter_ns;
  if (w > 0) {
    if (width_ns < w) return;
    if (period_ns - width_ns < w) {
      schedule(x, delay_ns, true);  // on for good, once the filter has seen it
      return;
    }
    delay_ns += w;
  }
  trains_.push_back({x, period_ns, width_ns, delay_ns});
  // A train on at its first instant (delay 0) has no edge after it that switches it on.
  if (trains_.back().level_at(ctx_.now())) schedule(x, ctx_.now(), true);
}

uint64_t TerminalEdges::next_event_ns() {
  prev_ns_ = ctx_.now();
  uint64_t t = kNever;
  if (!edges_.empty()) t = std::max(edges_.top().t, ctx_.now());
  for (const auto& tr : trains_) {
    bool up;
    if (!muted_[tr.x]) t = std::min(t, tr.next_after(ctx_.now(), &up));
  }
  return t;
}

std::vector<std::pair<int, bool>> TerminalEdges::take(uint64_t t) {
  std::vector<std::pair<int, bool>> group;
  for (const auto& tr : trains_) {
    bool up;
    if (!muted_[tr.x] && tr.next_after(prev_ns_, &up) == t) group.push_back({tr.x, up});
  }
  while (!edges_.empty() && edges_.top().t <= t) {
    const Edge e = edges_.top();
    edges_.pop();
    if (e.simulated) {
      sim_raw_[e.x] = e.level;
      if (muted_[e.x]) continue;
    }
    filter(e, &group);
  }
  return group;
}

// Unfiltered an edge acts now; filtered, it acts once the level has held for the filter
// width (a debounce: shorter pulses are lost, longer ones arrive that much late), unless
// the terminal changes back before.
void TerminalEdges::filter(const Edge& e, std::vector<std::pair<int, bool>>* group) {
  InputPin& p = pins_[e.x];
  if (e.commit) {
    if (e.gen == p.gen) group->push_back({e.x, e.level});
    return;
  }
  if (p.filter_ns == 0 || p.src) {
    group->push_back({e.x, e.level});
    return;
  }
  if (e.level == pins_.raw(e.x)) return;
  pins_.set_raw(e.x, e.level);
  ctx_.engine.set_input(e.x, e.level);
  ++p.gen;
  if (e.level != pins_.levels()[e.x]) edges_.push({e.t + p.filter_ns, seq_++, e.x, e.level, true, p.gen});
}

}  // namespace hsc
}  // namespace plc_cell
