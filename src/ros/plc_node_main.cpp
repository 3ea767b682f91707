#include <ros/ros.h>

#include "plc_cell/ros/plc_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "plc_node");
  ros::NodeHandle nh, pnh("~");
  try {
    plc_cell::PlcNode node(nh, pnh);
    ros::AsyncSpinner spinner(2);
    spinner.start();
    ros::waitForShutdown();
  } catch (const std::exception& e) {
    ROS_FATAL("plc_node: %s", e.what());
    return 1;
  }
  return 0;
}
