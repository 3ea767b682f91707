#include "plc_cell/ros/cell_node_main.h"
#include "plc_cell/ros/plc_node.h"

int main(int argc, char** argv) {
  // In virtual time every callback (clock, inputs, services, ~reset) runs on one thread,
  // one after the other: ~reset replaces the cell with nothing else using it.
  return plc_cell::run_cell_node<plc_cell::PlcNode>(
      argc, argv, "plc_node", [](ros::NodeHandle& pnh) { return pnh.param("virtual_time", false) ? 1 : 2; });
}
