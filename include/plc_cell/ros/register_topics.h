#pragma once
// plc_node's ~registers/<group> (plc_cell/RegisterBlock): the cell YAML's `registers:`
// groups, each read in one lock (one consistent image between two scans) at its rate,
// the same topics fatek_bridge publishes for a real PLC. In virtual time a group is
// published at its rate of virtual time, stamped with its scan.
#include <string>
#include <vector>

#include <ros/ros.h>

#include "plc_cell/config/register_groups.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {

class RegisterTopics {
 public:
  RegisterTopics(ros::NodeHandle& nh, ros::NodeHandle& pnh, SoftCell& cell, bool virtual_time);
  // Virtual time: called after the scan at now_us (lock not held).
  void after_virtual_scan(uint64_t now_us);

 private:
  struct Topic {
    RegisterGroup group;
    uint64_t period_us = 0, due_us = 0;
    ros::Publisher pub;
    ros::Timer timer;
  };
  void publish(Topic& t, const ros::Time& stamp);

  SoftCell& cell_;
  std::vector<Topic> topics_;
};

}  // namespace plc_cell
