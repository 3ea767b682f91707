#pragma once
// header.frame_id of everything a node publishes: ~frame_id, empty by default. A frame_id
// names a tf frame; a cell, link or channel name is not one, and a robot stack that
// transforms by frame_id would look it up and fail.
#include <string>

#include <ros/node_handle.h>

namespace plc_cell {

inline std::string frame_id_param(const ros::NodeHandle& pnh) {
  std::string frame;
  pnh.param<std::string>("frame_id", frame, "");
  return frame;
}

}  // namespace plc_cell
