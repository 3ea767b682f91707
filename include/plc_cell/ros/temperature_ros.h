#pragma once
// The temperature modules on ROS: one sensor_msgs/Temperature per named channel on
// ~temperature/<name>, ~temperature_inputs/<name> (what its sensor measures, from the
// stamp on), one /diagnostics status per module, and ~set_pid_loop: the ROS side of the
// modules extension, with none of these when the cell has no temperature modules.
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "plc_cell/SetPidLoop.h"
#include "plc_cell/ros/extension_ros.h"
#include "plc_cell/ros/topic_group.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {

class TemperatureRos : public TopicGroup {
 public:
  // Reads ~temperature_rate (Hz, default 1).
  TemperatureRos(ros::NodeHandle& pnh, SoftCell& cell, diagnostic_updater::Updater& updater, StampedInputs& inputs);
  double rate_hz() const override { return rate_hz_; }
  void publish(const ros::Time& stamp) override;
  std::vector<std::string> topics() const override;
  void rebind(SoftCell& cell) override { cell_ = &cell; }
  std::string layout(SoftCell& cell) const override;

 private:
  void diagnose_module(size_t module, diagnostic_updater::DiagnosticStatusWrapper& stat);
  bool on_set_loop(SetPidLoop::Request& req, SetPidLoop::Response& res);

  SoftCell* cell_;
  std::string frame_id_;
  double rate_hz_ = 1.0;
  std::vector<size_t> channel_;  // channel index of each publisher
  std::vector<ros::Publisher> pubs_;
  ros::ServiceServer set_loop_;
  std::vector<ros::Subscriber> input_subs_;
};

}  // namespace plc_cell
