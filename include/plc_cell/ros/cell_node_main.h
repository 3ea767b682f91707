#pragma once
// The main() of an executable that runs cells (plc_node, line_node): the node class in a
// process of its own (the same class is a nodelet too, src/ros/nodelets.cpp), stopped
// cleanly, every cell's store flushed, on SIGINT, SIGTERM or a shutdown request.
#include <ros/ros.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>

#include "plc_cell/io/stop_signal.h"

namespace plc_cell {

// threads(pnh): how many threads spin the node's callbacks.
template <class Node>
int run_cell_node(int argc, char** argv, const char* name, const std::function<int(ros::NodeHandle&)>& threads) {
  // Before ros::init and the node: every roscpp, scan and server thread inherits the
  // blocked SIGINT/SIGTERM, so a signal at any moment ends in the clean stop below (store
  // flushed). roscpp's own SIGINT handler is off; roslaunch's SIGTERM escalation would
  // otherwise kill the node without a flush.
  std::unique_ptr<StopSignal> stop;
  try {
    stop = std::make_unique<StopSignal>();
  } catch (const std::exception& e) {
    fprintf(stderr, "%s: %s\n", name, e.what());
    return 1;
  }
  ros::init(argc, argv, name, ros::init_options::NoSigintHandler);
  ros::NodeHandle nh, pnh("~");
  try {
    Node node(nh, pnh);
    ros::AsyncSpinner spinner(threads(pnh));
    spinner.start();
    // ros::ok() turns false on a shutdown request over XML-RPC (rosnode kill).
    while (ros::ok())
      if (stop->wait_for(std::chrono::milliseconds(100))) {
        ROS_INFO("%s: %s: stopping", name, stop->signal_name());
        break;
      }
    spinner.stop();
  } catch (const std::exception& e) {  // the node is gone by now: its store is flushed
    ROS_FATAL("%s: %s", name, e.what());
    ros::shutdown();
    return 1;
  }
  ros::shutdown();
  return 0;
}

}  // namespace plc_cell
