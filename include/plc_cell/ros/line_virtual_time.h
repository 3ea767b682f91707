#pragma once
// A line of cells on ROS in virtual time (~virtual_time: true on the line nodelet or
// line_node: docs/lines.md, "On ROS"): one clock for the whole line. Each message on
// ~clock_topic (default /clock) runs every instant of the line up to clock - ~virtual_time_lag
// through the core's Line::scan_at, so the cells scan in the order and with the wire
// deliveries of `plc_cell sim --line`; nothing here schedules a scan of its own.
//
// Each cell keeps a lone plc_node's virtual-time side (ros/virtual_time_driver.h): its
// stamped inputs are applied before its first scan at or after their stamp (a late one is
// applied at its next scan and counted on /diagnostics), its topics are published at its
// scans stamped with the clock time, and its ~virtual_time/scanned says how far it got. The
// line's time 0 is every cell's time 0. ~reset of one cell is refused: <line>/reset gives a
// fresh line, every cell at once (a wire holds the other cells' state).
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "plc_cell/line/line.h"
#include "plc_cell/ros/scan_driver.h"

namespace plc_cell {

class LineVirtualClock {
 public:
  // Reads ~clock_topic and ~virtual_time_lag from the line's private namespace; throws Error
  // on a bad lag.
  LineVirtualClock(ros::NodeHandle& pnh, const std::string& line_name, diagnostic_updater::Updater& updater);
  ~LineVirtualClock();
  // No clock message, input or progress after it returns: before the cells' nodes go.
  void stop();

  // The driver of cell i (its plc_node), before the clock starts. cell_pnh: the cell's
  // plc_node namespace, where its progress is published.
  std::unique_ptr<ScanDriver> driver(size_t cell, ros::NodeHandle& cell_pnh, ScanDriver::Host& host, uint64_t period_us);
  // Scans begin with the next clock message. line has run() already.
  void start(line::Line& line);
  // No clock message, input or scan runs during swap(), which puts a fresh line in place
  // (fresh cells under the same nodes); its time 0 is then the first scan that the next
  // clock message runs.
  void reset(line::Line& fresh, const std::function<void()>& swap);
  // The line's after_scan: cell's node publishes its scan (at line time t_us).
  void scanned(size_t cell, uint64_t t_us);
  const std::string& clock_topic() const { return clock_topic_; }
  double lag_s() const { return double(lag_us_) / 1e6; }

 private:
  class CellDriver;
  struct PerCell {
    CellDriver* driver = nullptr;
    uint64_t period_us = 0;
    uint64_t scans = 0, last_scan_us = 0;  // last_scan_us: clock time
    uint64_t input_seq = 0, inputs_received = 0, late_inputs = 0;
    std::vector<TimedInput> pending;
    ros::Publisher progress;
    std::string frame_id;
  };
  void on_clock(uint64_t now_us);
  void instant(uint64_t t_us);          // mu_ held: the line's instant at clock time t_us
  void input(size_t cell, TimedInput in);
  void publish_progress(size_t cell);   // mu_ held
  void clear_run();                     // mu_ held: a fresh run's counts

  std::string clock_topic_;
  uint64_t lag_us_ = 0;
  ros::NodeHandle pnh_;
  ros::Subscriber clock_sub_;
  std::mutex mu_;  // one clock message, input or reset at a time
  line::Line* line_ = nullptr;
  std::vector<PerCell> cells_;  // by the line's cell index; driver null: elsewhere
  bool started_ = false, after_reset_ = false, stopped_ = false;
  uint64_t epoch_us_ = 0, next_us_ = 0;  // clock times of the line's time 0 and next instant
  uint32_t resets_ = 0;
};

}  // namespace plc_cell
