#pragma once
// The scenario_runner on a line of cells in virtual time (a scenario file that names a line,
// the line nodelet with ~virtual_time: true: docs/lines.md, "A line's scenarios through ROS"):
// one clock for the whole line, one <line>/reset per case, and each cell watched through its
// own plc_node topics by a NodeLink (scenario_ros_target.h), as a lone node is. A step of the
// runner is one instant of the line (its tick); it is complete once every cell reported its
// last scan at or before it and every message of that scan arrived.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "plc_cell/line/line.h"
#include "plc_cell/ros/scenario_ros_target.h"
#include "plc_cell/scenario/routed_target.h"

namespace plc_cell {
namespace scenario {

class LineLink {
 public:
  // line: as the scenario's line file builds it (its cells' configs and periods); ns: where
  // the line runs ("/example_line"). Throws Error when a cell is not running there, runs
  // another cell or line file, or runs in real time.
  LineLink(const line::Line& line, const std::string& ns, double timeout_s, bool read_fallback);

  // Once: every cell hears the clock and its inputs, and every topic of a scan reaches the
  // runner. Throws Error saying what did not come.
  void connect();
  void begin_case();  // a fresh line (<line>/reset), its time 0 the next case's
  void scan(uint64_t t_us);
  uint64_t tick_us() const { return tick_us_; }
  size_t size() const { return cells_.size(); }
  const std::string& name(size_t i) const { return names_[i]; }
  NodeLink& cell(size_t i) { return *cells_[i]; }
  // The cell of a name's first part, or -1.
  int find(const std::string& cell) const;
  std::string names() const;  // "infeed, robot, test"

 private:
  void publish_clock(uint64_t t_us);
  void call_reset();
  void start_case(bool counted);  // every cell's time 0 at once

  std::string ns_;
  double timeout_s_;
  uint64_t tick_us_, lag_us_ = 0;
  std::vector<std::string> names_;
  std::vector<uint64_t> periods_;
  std::vector<std::unique_ptr<NodeLink>> cells_;
  ros::Publisher clock_pub_;  // through the first cell's link: its queue wakes the waits
  bool connected_ = false;
};

// One case on the line: every name CELL.NAME, read and driven through its cell's plc_node as
// a lone node's RosTarget does.
class LineRosTarget : public RoutedTarget {
 public:
  explicit LineRosTarget(LineLink& link);  // begins the case: a fresh line

  uint64_t period_us() const override { return link_.tick_us(); }
  void scan(uint64_t t_us) override { link_.scan(t_us); }
  std::string fault() override;

 private:
  Target* target_of(const std::string& cell, std::string* absent) override;
  std::string cell_names() const override { return link_.names(); }
  std::vector<Target*> cell_targets() override;

  LineLink& link_;
  std::vector<std::unique_ptr<RosTarget>> cells_;
};

}  // namespace scenario
}  // namespace plc_cell
