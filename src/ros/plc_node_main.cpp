#include <ros/ros.h>

#include <chrono>
#include <cstdio>
#include <memory>

#include "plc_cell/io/stop_signal.h"
#include "plc_cell/ros/plc_node.h"

int main(int argc, char** argv) {
  // Before ros::init and the node: every roscpp, scan and server thread inherits the
  // blocked SIGINT/SIGTERM, so a signal at any moment ends in the clean stop below (store
  // flushed). roscpp's own SIGINT handler is off; roslaunch's SIGTERM escalation would
  // otherwise kill the node without a flush.
  std::unique_ptr<plc_cell::StopSignal> stop;
  try {
    stop = std::make_unique<plc_cell::StopSignal>();
  } catch (const std::exception& e) {
    fprintf(stderr, "plc_node: %s\n", e.what());
    return 1;
  }
  ros::init(argc, argv, "plc_node", ros::init_options::NoSigintHandler);
  ros::NodeHandle nh, pnh("~");
  try {
    plc_cell::PlcNode node(nh, pnh);
    // In virtual time every callback (clock, inputs, services, ~reset) runs on one thread,
    // one after the other: ~reset replaces the cell with nothing else using it.
    ros::AsyncSpinner spinner(pnh.param("virtual_time", false) ? 1 : 2);
    spinner.start();
    // ros::ok() turns false on a shutdown request over XML-RPC (rosnode kill).
    while (ros::ok())
      if (stop->wait_for(std::chrono::milliseconds(100))) {
        ROS_INFO("plc_node: %s: stopping", stop->signal_name());
        break;
      }
    spinner.stop();
  } catch (const std::exception& e) {  // the node is gone by now: its store is flushed
    ROS_FATAL("plc_node: %s", e.what());
    ros::shutdown();
    return 1;
  }
  ros::shutdown();
  return 0;
}
