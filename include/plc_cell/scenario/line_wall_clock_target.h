#pragma once
// A line of cells, each a PLC over a link, as one wall-clock scenario target (docs/lines.md,
// "On ROS"): a wall-clock target per cell (wall_clock_target.h), each planning and polling
// the names of the case that start with its cell, and every name CELL.NAME routed to its
// cell's. One scan of the line polls every cell the case reads, one after the other; its
// instant is the latest of theirs. A name of a cell the line has not, or of one out of
// reach (not running where the runner looks), is refused by check() with the reason.
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/scenario/routed_target.h"
#include "plc_cell/scenario/wall_clock_target.h"

namespace plc_cell {
namespace scenario {

// One cell of the line as the runner reaches it.
struct LineCellLink {
  std::string name;                  // "robot": the first part of its names
  LinkedPlc* plc = nullptr;          // nullptr: out of reach (then `absent` says why)
  const CellConfig* config = nullptr;
  std::string absent;
};

class LineWallClockTarget : public RoutedTarget {
 public:
  // opt: as every cell's target takes them (each gets its own cell).
  LineWallClockTarget(const std::vector<LineCellLink>& cells, const Case& c, const WallClockOptions& opt);

  // What each cell's target will touch read, in the line's order, then their first polls,
  // all with one time 0.
  void begin();
  // The targets of the cells in reach, in the line's order, and the links they poll.
  size_t size() const { return targets_.size(); }
  WallClockTarget& cell(size_t i) { return *targets_[i]; }
  LinkedPlc& plc(size_t i) { return *links_[i]->plc; }
  uint64_t polls() const;

  uint64_t period_us() const override { return period_us_; }
  void scan(uint64_t t_us) override;
  uint64_t scanned_at(uint64_t t_us) const override;
  void simulate(const Probe* p) override;  // refused: no simulation on a PLC
  std::string fault() override { return ""; }
  // The widest of the cells' spreads, plus the round trips of the polls one after the other
  // that one reading of the line takes.
  uint64_t spread_us() override;

 private:
  Target* target_of(const std::string& cell, std::string* absent) override;
  std::string cell_names() const override { return names_; }
  std::vector<Target*> cell_targets() override;

  const std::vector<LineCellLink>& cells_;
  std::string names_;  // "infeed, robot, test"
  uint64_t period_us_ = 0;
  std::vector<const LineCellLink*> links_;                 // the cells in reach
  std::vector<std::unique_ptr<WallClockTarget>> targets_;  // theirs, in the same order
};

}  // namespace scenario
}  // namespace plc_cell
