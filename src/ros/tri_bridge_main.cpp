#include <ros/ros.h>

#include "plc_cell/ros/tri_bridge.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "tri_bridge");
  ros::NodeHandle nh, pnh("~");
  try {
    plc_cell::TriBridge node(nh, pnh);
    ros::AsyncSpinner spinner(2);
    spinner.start();
    ros::waitForShutdown();
  } catch (const std::exception& e) {
    ROS_FATAL("tri_bridge: %s", e.what());
    return 1;
  }
  return 0;
}
