#pragma once
// The scenario_runner on a line of cells on ROS (~real_time: true, a scenario file that names
// a line: docs/lines.md, "On ROS"): each cell of the line reached at <ns>/<cell>/plc_node
// through its own topics and services (TopicPlc), whichever process runs it, and the cases
// run on them all as one wall-clock target (scenario/line_wall_clock_target.h), under the
// rules of a lone node's run (scenario_real_time.h).
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/line/line.h"
#include "plc_cell/ros/scenario_real_time.h"
#include "plc_cell/scenario/line_wall_clock.h"

namespace plc_cell {
namespace scenario {

// The file's path with its links resolved (as given when it does not exist): two names of
// one file compare equal.
std::string real_path(const std::string& path);
// "/example_line/robot/plc_node": where the line nodelet runs the cell of the line at ns.
std::string node_of(const std::string& ns, const std::string& cell);
// The line's nodes say which cell they run (~cell) as they start, perhaps after the runner:
// waits up to timeout_s for every cell of line to say it, polling.
void wait_for_cells(const line::Line& line, const std::string& ns, double timeout_s);

class LineRealTimeRun : public RealTimeCases {
 public:
  // sc names a line; ns: where it runs ("/example_line"). Connects to the cells the cases
  // name, measures the resolution and checks every case. Throws Error when a node cannot be
  // reached, or runs another cell or line than sc's; a cell not running on ROS is refused at
  // the names of it (refusals()).
  LineRealTimeRun(const Scenario& sc, const std::string& ns, double timeout_s, uint64_t tolerance_us,
                  const std::atomic<int>* stop);

  const std::string& target() const override { return target_; }  // "ros:/example_line"
  const Resolution& resolution() const override { return resolution_; }
  const std::string& refusals() const override { return refusals_; }
  RealTimeOutcome run(const Case& c) override;
  bool says_forced() const override { return says_forced_; }
  std::vector<std::string> not_as_found() override;

 private:
  // The cell i of the line at ns as the runner reaches it (plc null: out of reach).
  LineCellLink reach(size_t i, const std::string& ns, double timeout_s);

  std::unique_ptr<line::Line> line_;  // the cells as the line file builds them: their configs
  std::string target_, refusals_;
  std::vector<std::unique_ptr<TopicPlc>> plcs_;  // by cell; null when out of reach or unused
  std::vector<LineCellLink> cells_;
  Resolution resolution_;
  std::vector<Case> cases_;  // as run: windows widened
  std::vector<StepNote> widened_;
  std::vector<std::vector<FoundPoint>> before_;  // by cell: its touched points before the first case
  bool says_forced_ = true;
  const std::atomic<int>* stop_;
};

}  // namespace scenario
}  // namespace plc_cell
