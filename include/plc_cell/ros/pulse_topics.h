#pragma once
// The pulse measurement of the cell's counter inputs on ROS (counters.pulse_measurement):
// ~pulses/<input> (PulseMeasurement), one per measured input, beside ~counters and at
// their rate.
#include <string>
#include <vector>

#include <ros/ros.h>

#include "plc_cell/ros/topic_group.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {

class PulseTopics : public TopicGroup {
 public:
  // rate_hz <= 0: the config's counters.publish_rate (as CounterTopics).
  PulseTopics(ros::NodeHandle& pnh, SoftCell& cell, double rate_hz);
  double rate_hz() const override { return rate_hz_; }
  void publish(const ros::Time& stamp) override;
  std::vector<std::string> topics() const override;
  void rebind(SoftCell& cell) override { cell_ = &cell; }
  std::string layout(SoftCell& cell) const override;

 private:
  SoftCell* cell_;
  std::string frame_id_;
  double rate_hz_;
  std::vector<int> inputs_;
  std::vector<std::string> counters_;  // the counter each input counts for
  std::string unit_;
  bool tenths_ = false;
  std::vector<ros::Publisher> pubs_;
};

}  // namespace plc_cell
