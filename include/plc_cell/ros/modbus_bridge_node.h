#pragma once
// modbus_bridge: a thin ROS layer over modbus::Bridge. Per point a typed std_msgs
// topic ~<device>/<point>, per read a plc_cell/RegisterBlock on ~<device>/blocks,
// ~write_point (plc_cell/WritePoint), ~recover (std_srvs/Trigger), /diagnostics per device.
#include <memory>
#include <mutex>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "plc_cell/WritePoint.h"
#include "plc_cell/modbus/bridge.h"

namespace plc_cell {

class ModbusBridgeNode {
 public:
  // Reads ~config (the bridge YAML path); throws on bad input.
  ModbusBridgeNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  ~ModbusBridgeNode();

 private:
  struct PointState {
    ros::Publisher pub;
    bool has = false;
    uint64_t raw = 0;
  };
  void on_result(const modbus::GroupResult& r);
  void publish_point(const modbus::Point& p, PointState& st, const modbus::Value& v, double eng);
  bool on_write(WritePoint::Request& req, WritePoint::Response& res);
  void diagnose(size_t device, diagnostic_updater::DiagnosticStatusWrapper& stat);

  std::unique_ptr<modbus::Bridge> bridge_;
  std::vector<std::vector<std::vector<PointState>>> points_;  // [device][group][point]
  std::vector<std::vector<ros::Time>> last_full_;             // [device][group]
  std::vector<ros::Publisher> block_pubs_;                     // per device
  std::mutex mu_;
  std::string frame_id_;
  std::vector<ros::ServiceServer> services_;
  diagnostic_updater::Updater updater_;
  ros::Timer diag_timer_;
};

}  // namespace plc_cell
