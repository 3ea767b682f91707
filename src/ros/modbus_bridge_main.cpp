#include "plc_cell/ros/node_main.h"
#include "plc_cell/ros/modbus_bridge_node.h"

int main(int argc, char** argv) { return plc_cell::run_node<plc_cell::ModbusBridgeNode>(argc, argv, "modbus_bridge"); }
