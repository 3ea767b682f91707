// line_node: a line of cells (ros/line_node.h) in a process of its own, as the line nodelet
// runs it in a manager: `rosrun plc_cell line_node _line:=FILE [_cells:=infeed,robot]`.
#include "plc_cell/ros/cell_node_main.h"
#include "plc_cell/ros/line_node.h"

int main(int argc, char** argv) {
  // In virtual time one thread: <line>/reset swaps every cell with no service of a cell in
  // flight (as plc_node's ~reset).
  return plc_cell::run_cell_node<plc_cell::LineNode>(
      argc, argv, "line_node", [](ros::NodeHandle& pnh) { return pnh.param("virtual_time", false) ? 1 : 2; });
}
