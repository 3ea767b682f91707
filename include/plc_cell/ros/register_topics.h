#pragma once
// plc_node's ~registers/<group> (plc_cell/RegisterBlock): the cell YAML's `registers:`
// groups, each read in one lock (one consistent image between two scans) at its rate,
// the same topics fatek_bridge publishes for a real PLC.
#include <string>

#include <ros/ros.h>

#include "plc_cell/config/register_groups.h"
#include "plc_cell/ros/topic_group.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {

// One group: each has its own rate, so each is its own TopicGroup.
class RegisterTopic : public TopicGroup {
 public:
  RegisterTopic(ros::NodeHandle& pnh, SoftCell& cell, const RegisterGroup& group);
  double rate_hz() const override { return group_.rate_hz; }
  void publish(const ros::Time& stamp) override;
  std::vector<std::string> topics() const override { return {pub_.getTopic()}; }
  void rebind(SoftCell& cell) override { cell_ = &cell; }

 private:
  SoftCell* cell_;
  RegisterGroup group_;
  ros::Publisher pub_;
  std::string frame_id_;
};

// A RegisterTopic for every group of the cell.
void add_register_topics(ros::NodeHandle& pnh, SoftCell& cell, TopicGroups* groups);

}  // namespace plc_cell
