#pragma once
// fatek_bridge: a thin ROS layer over fatek::Bridge (the bus side), with the topics and
// services of plc_node: ~io, ~signals/<name>, ~signals_stamped/<name>, ~registers/<group>,
// ~read, ~write, ~force, ~release, ~set_run_mode, ~recover, and the link on /diagnostics.
#include <memory>
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "plc_cell/fatek/bridge.h"
#include "plc_cell/ros/bridge_topics.h"
#include "plc_cell/ros/memory_services.h"

namespace plc_cell {

class FatekBridge : private MemoryAccess {
 public:
  // Reads ~tcp or ~port/~baud/~format, ~station, ~timeout, ~retries, ~io_rate,
  // ~max_backoff and ~config (YAML of signals and poll groups); throws on bad input.
  FatekBridge(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  ~FatekBridge();

 private:
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);
  // plc_node's ~read, ~write, ~force and ~release over the link (fatek_bridge_services.cpp,
  // ros/memory_services.h).
  Address resolve(const std::string& text) const override;
  std::vector<uint32_t> read(const Address& start, uint32_t count) override;
  void write(const Address& start, const std::vector<uint32_t>& raw) override;
  void force(const Address& bit, bool value) override;
  std::vector<Address> release(const Address* bit) override;
  bool reads_forced() const override { return true; }
  std::vector<bool> forced(const std::vector<Address>& bits) override;

  std::unique_ptr<BridgeTopics> topics_;  // before the bridge whose sinks reach it
  std::unique_ptr<fatek::Bridge> bridge_;
  std::vector<ros::ServiceServer> services_;
  diagnostic_updater::Updater updater_;
  ros::Timer diag_timer_;
};

}  // namespace plc_cell
