#pragma once
// tri_bridge: a thin ROS layer over tri::Bridge (the bus side), with the topics and
// services of plc_node for what a TRi has: ~io, ~signals/<name>, ~signals_stamped/<name>,
// ~registers/<group>, ~read, ~write, ~force, ~release, ~set_run_mode, ~recover, and the
// link on /diagnostics (docs/tri.md, "tri_bridge").
#include <memory>
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "plc_cell/ros/bridge_topics.h"
#include "plc_cell/ros/memory_services.h"
#include "plc_cell/tri/bridge.h"

namespace plc_cell {

class TriBridge : private MemoryAccess {
 public:
  // Reads ~tcp or ~port/~baud/~format, ~id, ~timeout, ~retries, ~io_rate, ~max_backoff
  // and ~config (YAML of io, signals and groups); throws on bad input.
  TriBridge(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  ~TriBridge();

 private:
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);
  // plc_node's ~read, ~write, ~force and ~release over the host link.
  Address resolve(const std::string& text) const override { return bridge_->resolve(text); }
  std::vector<uint32_t> read(const Address& start, uint32_t count) override { return bridge_->read(start, count); }
  void write(const Address& start, const std::vector<uint32_t>& raw) override { bridge_->write(start, raw); }
  void force(const Address& bit, bool value) override { bridge_->force(bit, value); }
  std::vector<Address> release(const Address* bit) override { return bridge_->release(bit); }

  std::unique_ptr<BridgeTopics> topics_;  // before the bridge whose sinks reach it
  std::unique_ptr<tri::Bridge> bridge_;
  std::vector<ros::ServiceServer> services_;
  diagnostic_updater::Updater updater_;
  ros::Timer diag_timer_;
};

}  // namespace plc_cell
