#include <ros/ros.h>

#include "plc_cell/ros/modbus_bridge_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "modbus_bridge");
  ros::NodeHandle nh, pnh("~");
  try {
    plc_cell::ModbusBridgeNode node(nh, pnh);
    ros::AsyncSpinner spinner(2);
    spinner.start();
    ros::waitForShutdown();
  } catch (const std::exception& e) {
    ROS_FATAL("modbus_bridge: %s", e.what());
    return 1;
  }
  return 0;
}
