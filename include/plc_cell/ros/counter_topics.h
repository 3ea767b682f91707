#pragma once
// The cell's high-speed counters on ROS: ~counters (CounterArray, all counters),
// ~counters/<name> (Counter, one per configured counter), ~counters/<name>/preset
// (PresetCounter), ~counters/<name>/clear (std_srvs/Trigger) and, per simulated
// pulse source, ~sources/<name>/rate (std_msgs/Float64, periods per second). With the
// pulse measurement's PulseTopics, the ROS side of the counters extension.
#include <string>
#include <vector>

#include <ros/ros.h>

#include "plc_cell/ros/topic_group.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {

class CounterTopics : public TopicGroup {
 public:
  // rate_hz <= 0: the config's counters.publish_rate.
  CounterTopics(ros::NodeHandle& pnh, SoftCell& cell, double rate_hz);
  double rate_hz() const override { return rate_hz_; }
  // CounterArray and every Counter carry the same header.
  void publish(const ros::Time& stamp) override;
  std::vector<std::string> topics() const override;
  void rebind(SoftCell& cell) override { cell_ = &cell; }
  std::string layout(SoftCell& cell) const override;

 private:
  SoftCell* cell_;
  std::string frame_id_;
  double rate_hz_;
  std::vector<int> numbers_;  // configured counters, in order
  std::vector<std::string> names_;
  ros::Publisher all_pub_;
  std::vector<ros::Publisher> one_pubs_;
  std::vector<ros::ServiceServer> services_;
  std::vector<ros::Subscriber> subs_;
};

}  // namespace plc_cell
