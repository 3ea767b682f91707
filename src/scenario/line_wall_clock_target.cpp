#include "plc_cell/scenario/line_wall_clock_target.h"

#include <algorithm>

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

WallClockTarget* LineWallClockTarget::cell_of(const Probe& p, std::string* why) {
  if (p.cell.empty()) {
    *why = "'" + p.text + "': a line's names start with their cell: CELL." + p.text + " (cells: " + names_ + ")";
    return nullptr;
  }
  for (size_t i = 0; i < targets_.size(); ++i)
    if (links_[i]->name == p.cell) return targets_[i].get();
  for (const auto& l : cells_)
    if (l.name == p.cell) {
      *why = "'" + p.text + "': " + l.absent;
      return nullptr;
    }
  *why = "'" + p.text + "': no cell '" + p.cell + "' in the line (" + names_ + ")";
  return nullptr;
}

WallClockTarget& LineWallClockTarget::cell_or_throw(const Probe& p) {
  std::string why;
  WallClockTarget* t = cell_of(p, &why);
  if (!t) throw Error(why);
  return *t;
}

std::string LineWallClockTarget::check(const Probe& p, bool writing) {
  std::string why;
  WallClockTarget* t = cell_of(p, &why);
  if (!t) return why;
  why = t->check(p, writing);
  return why.empty() ? why : p.cell + ": " + why;
}

void LineWallClockTarget::release(const Probe* p) {
  if (p) return cell_or_throw(*p).release(p);
  for (auto& t : targets_) t->release(nullptr);
}

void LineWallClockTarget::simulate(const Probe*) {
  throw Error("a line on its PLCs has no simulation to hand inputs back to");
}

std::string LineWallClockTarget::label(const Probe& p) {
  std::string why;
  WallClockTarget* t = cell_of(p, &why);
  if (!t) return p.text;
  const std::string l = t->label(p);
  return l == p.text ? l : p.cell + "." + l;
}

}  // namespace scenario
}  // namespace plc_cell
