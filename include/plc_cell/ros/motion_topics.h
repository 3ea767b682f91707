#pragma once
// The pulse-output axes on ROS (docs/motion.md "ROS"): joint_states in the node's
// namespace (sensor_msgs/JointState in m or rad, every axis of the cell YAML's axes: section),
// ~motion/<axis>/status (AxisStatus), services ~motion/<axis>/load_table,
// set_params, command, and the action ~motion/<axis>/run (RunMotionTable).
#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "plc_cell/MotionCommand.h"
#include "plc_cell/RunMotionTableAction.h"
#include "plc_cell/SetMotionParams.h"
#include "plc_cell/motion/axis_config.h"
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
  std::string layout(SoftCell& cell) const override;

 private:
  struct AxisRos;

  // f(MotionUnit&) under the PLC lock.
  template <class F>
  auto locked(F&& f);
  std::unique_ptr<AxisRos> make_axis(ros::NodeHandle& pnh, int n, const motion::AxisDef& d);
  bool set_params(int n, SetMotionParams::Request& req, SetMotionParams::Response& res);
  bool command(int n, MotionCommand::Request& req, MotionCommand::Response& res);
  void run_goal(AxisRos* ar, const RunMotionTableGoalConstPtr& goal);
  void follow_goal(AxisRos* ar, RunMotionTableResult* result);

  SoftCell* cell_;
  std::string frame_id_;
  double rate_hz_;
  std::vector<std::unique_ptr<AxisRos>> axes_;
  ros::Publisher joints_pub_;
};

}  // namespace plc_cell
