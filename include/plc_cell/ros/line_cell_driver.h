#pragma once
// plc_node's ROS side on a cell of a line (ros/line_node.h): the line scans the cell, in
// real time, on the thread the line gives it, and carries its wires; after each scan the
// line node hands the scan to this driver, which publishes as the real-time driver does
// (the same ~clock, the same stamps, the same queue). So a cell of a line has a lone
// plc_node's topics, and only the line decides when it scans.
#include <string>

#include "plc_cell/ros/real_time_driver.h"

namespace plc_cell {

class LineCellDriver : public RealTimeDriver {
 public:
  using RealTimeDriver::RealTimeDriver;

  void start() override {}  // the line starts every cell's scans at once
  void stop() override {}   // and stops them before its cells' nodes go
  // On the cell's scan thread, after the line carried the scan's wires.
  void scanned() { after_scan(); }
  std::string reset_refusal() const override {
    return "~reset: this cell is part of a line, whose wires hold the other cells' state; restart the line for "
           "fresh cells";
  }
};

}  // namespace plc_cell
