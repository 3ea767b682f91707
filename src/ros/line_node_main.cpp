// line_node: a line of cells (ros/line_node.h) in a process of its own, as the line nodelet
// runs it in a manager: `rosrun plc_cell line_node _line:=FILE [_cells:=infeed,robot]`.
#include <ros/ros.h>

#include <chrono>
#include <cstdio>
#include <memory>

#include "plc_cell/io/stop_signal.h"
#include "plc_cell/ros/line_node.h"

int main(int argc, char** argv) {
  // As plc_node: the signals blocked before any thread starts, so that a stop at any moment
  // ends in the clean stop below (every cell's store flushed).
  std::unique_ptr<plc_cell::StopSignal> stop;
  try {
    stop = std::make_unique<plc_cell::StopSignal>();
  } catch (const std::exception& e) {
    fprintf(stderr, "line_node: %s\n", e.what());
    return 1;
  }
  ros::init(argc, argv, "line_node", ros::init_options::NoSigintHandler);
  ros::NodeHandle nh, pnh("~");
  try {
    plc_cell::LineNode node(nh, pnh);
    ros::AsyncSpinner spinner(2);
    spinner.start();
    while (ros::ok())
      if (stop->wait_for(std::chrono::milliseconds(100))) {
        ROS_INFO("line_node: %s: stopping", stop->signal_name());
        break;
      }
    spinner.stop();
  } catch (const std::exception& e) {
    ROS_FATAL("line_node: %s", e.what());
    ros::shutdown();
    return 1;
  }
  ros::shutdown();
  return 0;
}
