#pragma once
// plc_node's cell in virtual time (~virtual_time: true): no real-time loop. Each message on
// ~clock_topic (rosgraph_msgs/Clock, default /clock, e.g. `rosbag play --clock`) runs every
// scan at times k * scan_period up to clock - ~virtual_time_lag (the cell's own time
// starting at 0 at the first clock message, or after ~reset at its first scan). Stamped
// inputs are applied before the first scan at or after their stamp, and every topic is
// published at its scan, stamped with the scan's clock time, on the clock's thread. So the
// same inputs and clock give the same outputs on every topic, bit for bit.
// The lag lets inputs that travel on other connections than the clock arrive first; an
// input that still comes after its scan is applied at the next one and counted as late
// (on /diagnostics), since from then on a replay may differ.
//
// ~virtual_time/scanned (ScanProgress) says how far the node got and how many messages it
// published on each topic, so a test driver knows when every message of a scan has arrived.
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "plc_cell/ros/scan_driver.h"

namespace plc_cell {

class VirtualTimeDriver : public ScanDriver {
 public:
  // Reads ~clock_topic and ~virtual_time_lag; throws Error on a bad lag.
  VirtualTimeDriver(ros::NodeHandle& pnh, Host& host, diagnostic_updater::Updater& updater, uint64_t period_us,
                    std::string frame_id);

  void start() override;
  void input(TimedInput in) override;
  ros::Time stamp(uint64_t cell_us) const override;
  void post(std::function<void()> fn) override { fn(); }  // on the clock's thread, at the scan
  bool republishes() const override { return false; }     // a republish is not a replay's
  std::string reset_refusal() const override { return ""; }
  void reset(const std::function<void()>& swap) override;

 private:
  // One cell's run on the clock: ~reset starts a fresh one.
  struct Run {
    explicit Run(bool reset) : after_reset(reset) {}
    bool after_reset;      // its time 0 is its first scan, not the first clock message
    bool started = false;  // a clock message set its time 0
    uint64_t epoch_us = 0;  // the clock time of the cell's time 0
    uint64_t next_scan_us = 0, last_scan_us = 0, scans = 0;
    uint64_t input_seq = 0, inputs_received = 0, late_inputs = 0;
    std::vector<TimedInput> pending;  // until the scan at or after their stamp
  };
  void on_clock(uint64_t now_us);
  void scan(uint64_t t);          // the scan at clock time t (mu_ held)
  void publish_progress();        // ~virtual_time/scanned (mu_ held)

  Host& host_;
  std::string clock_topic_, frame_id_;
  uint64_t period_us_, lag_us_ = 0;
  ros::Publisher scanned_pub_;
  ros::Subscriber clock_sub_;
  ros::NodeHandle pnh_;
  std::mutex mu_;  // one clock message, input or reset at a time
  std::unique_ptr<Run> run_ = std::make_unique<Run>(false);
  uint32_t resets_ = 0;
};

}  // namespace plc_cell
