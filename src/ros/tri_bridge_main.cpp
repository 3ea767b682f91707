#include "plc_cell/ros/node_main.h"
#include "plc_cell/ros/tri_bridge.h"

int main(int argc, char** argv) { return plc_cell::run_node<plc_cell::TriBridge>(argc, argv, "tri_bridge"); }
