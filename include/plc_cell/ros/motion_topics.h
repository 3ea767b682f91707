#pragma once
// The pulse-output axes on ROS (docs/motion.md "ROS"): joint_states in the node's
// namespace (sensor_msgs/JointState in m or rad, every axis of the cell YAML's axes: section),
// ~motion/<axis>/status (AxisStatus), services ~motion/<axis>/load_table,
// set_params, command, and the action ~motion/<axis>/run (RunMotionTable).
#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "plc_cell/ros/topic_group.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {

class MotionTopics : public TopicGroup {
 public:
  MotionTopics(ros::NodeHandle& nh, ros::NodeHandle& pnh, SoftCell& cell, double rate_hz);
  ~MotionTopics() override;
  double rate_hz() const override { return rate_hz_; }
  // JointState and every AxisStatus carry the same header; nothing without axes.
  void publish(const ros::Time& stamp) override;
  std::vector<std::string> topics() const override;
  void rebind(SoftCell& cell) override { cell_ = &cell; }

 private:
  struct AxisRos;

  SoftCell* cell_;
  std::string frame_id_;
  double rate_hz_;
  std::vector<std::unique_ptr<AxisRos>> axes_;
  ros::Publisher joints_pub_;
};

}  // namespace plc_cell
