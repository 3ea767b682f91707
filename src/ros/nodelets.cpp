// plc_node, fatek_bridge, tri_bridge, modbus_bridge and line_node as nodelets (nodelet_plugins.xml):
// many cells and bridges in one process (a nodelet manager), each with its own private
// namespace, parameters, topics and /diagnostics entries, as the executables have. The
// executables build the same classes in a process of their own.
#include <memory>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "plc_cell/ros/fatek_bridge.h"
#include "plc_cell/ros/line_node.h"
#include "plc_cell/ros/modbus_bridge_node.h"
#include "plc_cell/ros/plc_node.h"
#include "plc_cell/ros/tri_bridge.h"

namespace plc_cell {

// Whether the node needs its callbacks one at a time: plc_node in virtual time, whose
// ~reset replaces the cell with no other callback using it, and the line node in virtual
// time, whose <line>/reset replaces every cell (their executables spin one thread then).
template <class Node>
bool one_thread(ros::NodeHandle&) {
  return false;
}
template <>
bool one_thread<PlcNode>(ros::NodeHandle& pnh) {
  return pnh.param("virtual_time", false);
}
template <>
bool one_thread<LineNode>(ros::NodeHandle& pnh) {
  return pnh.param("virtual_time", false);
}

// A node class built on the manager's multi-threaded queue, as the executables spin it
// (an AsyncSpinner): its scans post their publishing there, its services run there. Or on
// the nodelet's single-threaded queue, when it needs one thread.
template <class Node>
class NodeNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    try {
      if (one_thread<Node>(getPrivateNodeHandle()))
        node_ = std::make_unique<Node>(getNodeHandle(), getPrivateNodeHandle());
      else
        node_ = std::make_unique<Node>(getMTNodeHandle(), getMTPrivateNodeHandle());
    } catch (const std::exception& e) {
      NODELET_FATAL("%s", e.what());
      throw;  // the manager refuses to load it, and says so to the loader
    }
  }
  std::unique_ptr<Node> node_;
};

using PlcNodelet = NodeNodelet<PlcNode>;
using FatekBridgeNodelet = NodeNodelet<FatekBridge>;
using TriBridgeNodelet = NodeNodelet<TriBridge>;
using ModbusBridgeNodelet = NodeNodelet<ModbusBridgeNode>;
using LineNodelet = NodeNodelet<LineNode>;  // a line's cells, each a plc_node (ros/line_node.h)

}  // namespace plc_cell

PLUGINLIB_EXPORT_CLASS(plc_cell::PlcNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(plc_cell::FatekBridgeNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(plc_cell::TriBridgeNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(plc_cell::ModbusBridgeNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(plc_cell::LineNodelet, nodelet::Nodelet)
