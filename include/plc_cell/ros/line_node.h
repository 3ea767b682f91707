#pragma once
// A line of cells on ROS (docs/lines.md, "On ROS"): the cells of a line file named by
// ~cells (default every cell), built and wired by the core's Line (line/line.h) and scanned
// in real time, or with ~virtual_time on the line's one clock (ros/line_virtual_time.h),
// each with a lone plc_node's topics and services under <namespace>/<line>/<cell>/plc_node/.
// The wires between two cells here are carried inside the process; a wire with its other
// end in another process, on a ROS topic (ros/line_wire_topics.h). The line nodelet
// (plc_cell/LineNodelet) builds one. In virtual time its callbacks run one at a time (the
// nodelet's single-threaded queue, line_node's one spinner thread): <line>/reset replaces
// every cell with no service of a cell in flight.
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "plc_cell/line/line.h"
#include "plc_cell/ros/line_cell_driver.h"
#include "plc_cell/ros/line_virtual_time.h"
#include "plc_cell/ros/line_wire_topics.h"
#include "plc_cell/ros/plc_node.h"

namespace plc_cell {

class LineNode {
 public:
  // Reads ~line (the line file), ~cells ("infeed,robot" or a list; empty: every cell),
  // ~shared_scan, ~shared_scan_threads, ~virtual_time (with ~clock_topic and
  // ~virtual_time_lag); throws Error (SourceError at the line file's
  // file:line) on bad input, with nothing left running.
  LineNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  ~LineNode();  // the scans stop first, then the cells' nodes, then the cells
  LineNode(const LineNode&) = delete;
  LineNode& operator=(const LineNode&) = delete;

 private:
  // The cells named by ~cells (checked by the line against its file).
  static std::set<std::string> cells_param(ros::NodeHandle& pnh);
  void add_cell(ros::NodeHandle& nh, size_t i);
  void start_real_time(ros::NodeHandle& nh, unsigned shared_threads);
  // Virtual time: refused when a wire crosses to a cell of another process; else the clock.
  void start_virtual_time(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  // <line>/reset in virtual time: a fresh line from the same files under the same topics.
  bool on_reset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);

  line::LineOptions options_;

  std::unique_ptr<line::Line> line_;
  std::vector<std::unique_ptr<PlcNode>> nodes_;  // per cell of the line; none: elsewhere
  std::vector<LineCellDriver*> drivers_;         // real time: each node's driver, for the line's scans
  std::unique_ptr<LineVirtualClock> clock_;      // virtual time: the line's one clock
  ros::ServiceServer reset_srv_;
  std::mutex reset_mu_;  // one <line>/reset at a time (a manager serves calls on several threads)
  std::unique_ptr<LineWireTopics> wires_;
  diagnostic_updater::Updater updater_;  // "<nodelet>: wires" on /diagnostics
  ros::Timer diag_timer_;
};

}  // namespace plc_cell
