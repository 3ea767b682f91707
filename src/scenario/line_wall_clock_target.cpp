#include "plc_cell/scenario/line_wall_clock_target.h"

#include <algorithm>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace scenario {

LineWallClockTarget::LineWallClockTarget(const std::vector<LineCellLink>& cells, const Case& c,
                                         const WallClockOptions& opt)
    : cells_(cells), period_us_(opt.period_us) {
  for (const auto& l : cells) {
    names_ += (names_.empty() ? "" : ", ") + l.name;
    if (!l.plc) continue;
    WallClockOptions mine = opt;
    mine.cell = l.name;
    links_.push_back(&l);
    targets_.push_back(std::make_unique<WallClockTarget>(*l.plc, *l.config, c, mine));
  }
}

// Every cell's points read first (a link may take a while to say which are forced), then one
// time 0 for all: the cells' polls of one scan are instants of the same case clock.
void LineWallClockTarget::begin() {
  for (auto& t : targets_) t->find();
  const auto zero = std::chrono::steady_clock::now();
  for (auto& t : targets_) t->start(zero);
}

uint64_t LineWallClockTarget::polls() const {
  uint64_t n = 0;
  for (const auto& t : targets_) n = std::max(n, t->polls());
  return n;
}

void LineWallClockTarget::scan(uint64_t t_us) {
  for (auto& t : targets_) t->scan(t_us);
}

uint64_t LineWallClockTarget::scanned_at(uint64_t t_us) const {
  uint64_t at = 0;
  for (const auto& t : targets_) at = std::max(at, t->scanned_at(t_us));
  return at;
}

uint64_t LineWallClockTarget::spread_us() {
  uint64_t widest = 0, polls = 0;
  for (auto& t : targets_) {
    widest = std::max(widest, t->spread_us());
    polls += t->slowest_poll_us();
  }
  return widest + polls;
}

Target* LineWallClockTarget::target_of(const std::string& cell, std::string* absent) {
  for (size_t i = 0; i < targets_.size(); ++i)
    if (links_[i]->name == cell) return targets_[i].get();
  for (const auto& l : cells_)
    if (l.name == cell) *absent = l.absent;
  return nullptr;
}

std::vector<Target*> LineWallClockTarget::cell_targets() {
  std::vector<Target*> out;
  for (auto& t : targets_) out.push_back(t.get());
  return out;
}

void LineWallClockTarget::simulate(const Probe*) {
  throw Error("a line on its PLCs has no simulation to hand inputs back to");
}

}  // namespace scenario
}  // namespace plc_cell
