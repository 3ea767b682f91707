#include <ros/ros.h>

#include "plc_cell/ros/fatek_bridge.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "fatek_bridge");
  ros::NodeHandle nh, pnh("~");
  try {
    plc_cell::FatekBridge node(nh, pnh);
    ros::AsyncSpinner spinner(2);
    spinner.start();
    ros::waitForShutdown();
  } catch (const std::exception& e) {
    ROS_FATAL("fatek_bridge: %s", e.what());
    return 1;
  }
  return 0;
}
