#pragma once
// The main() of a bridge executable: the node class in a process of its own, spun by two
// threads (the same class is a nodelet too, src/ros/nodelets.cpp).
#include <ros/ros.h>

namespace plc_cell {

template <class Node>
int run_node(int argc, char** argv, const char* name) {
  ros::init(argc, argv, name);
  ros::NodeHandle nh, pnh("~");
  try {
    Node node(nh, pnh);
    ros::AsyncSpinner spinner(2);
    spinner.start();
    ros::waitForShutdown();
  } catch (const std::exception& e) {
    ROS_FATAL("%s: %s", name, e.what());
    return 1;
  }
  return 0;
}

}  // namespace plc_cell
