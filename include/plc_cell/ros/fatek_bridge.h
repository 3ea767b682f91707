#pragma once
// fatek_bridge: a thin ROS layer over fatek::Bridge (the bus side), with the topics and
// services of plc_node: ~io, ~signals/<name>, ~signals_stamped/<name>, ~registers/<group>,
// ~read, ~write, ~force, ~release, ~set_run_mode, ~recover, and the link on /diagnostics.
#include <memory>
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include "plc_cell/fatek/bridge.h"
#include "plc_cell/ros/memory_services.h"

namespace plc_cell {

class FatekBridge : private MemoryAccess {
 public:
  // Reads ~tcp or ~port/~baud/~format, ~station, ~timeout, ~retries, ~io_rate,
  // ~max_backoff and ~config (YAML of signals and poll groups); throws on bad input.
  FatekBridge(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  ~FatekBridge();

 private:
  void on_io(const fatek::IoResult& r);
  void on_group(const fatek::GroupResult& r);
  void publish_signal(size_t i, bool on, const ros::Time& stamp);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);
  bool on_run(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res);
  bool on_recover(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  // plc_node's ~read, ~write, ~force and ~release over the link (fatek_bridge_services.cpp,
  // ros/memory_services.h).
  Address resolve(const std::string& text) const override;
  std::vector<uint32_t> read(const Address& start, uint32_t count) override;
  void write(const Address& start, const std::vector<uint32_t>& raw) override;
  void force(const Address& bit, bool value) override;
  std::vector<Address> release(const Address* bit) override;

  std::unique_ptr<fatek::Bridge> bridge_;
  ros::Publisher io_pub_;
  std::vector<ros::Publisher> group_pubs_;    // ~registers/<group>
  std::vector<ros::Publisher> signal_pubs_;   // ~signals/<name>
  std::vector<ros::Publisher> stamped_pubs_;  // ~signals_stamped/<name>
  std::string frame_id_;                      // ~frame_id of every header
  std::vector<int> last_signals_;             // -1 before the first poll; the bridge's thread only
  std::vector<ros::ServiceServer> services_;
  diagnostic_updater::Updater updater_;
  ros::Timer diag_timer_;
};

}  // namespace plc_cell
