#include "plc_cell/ros/node_main.h"
#include "plc_cell/ros/fatek_bridge.h"

int main(int argc, char** argv) { return plc_cell::run_node<plc_cell::FatekBridge>(argc, argv, "fatek_bridge"); }
