#pragma once
// fatek_bridge: a real FATEK PLC (serial or TCP) on ROS with the topics of plc_node.
// A worker thread owns the link: it polls groups at their rates (coalesced frames),
// reconnects with back-off, and services run their transactions between polls.
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include "plc_cell/fatek/client.h"
#include "plc_cell/fatek/poll_plan.h"
#include "plc_cell/ros/memory_services.h"

namespace plc_cell {

class FatekBridge : private MemoryAccess {
 public:
  // Reads ~tcp or ~port/~baud/~format, ~station, ~timeout, ~retries, ~io_rate,
  // ~max_backoff and ~config (YAML of signals and poll groups); throws on bad input.
  FatekBridge(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  ~FatekBridge();

 private:
  struct Group {
    std::string name, text;
    double period = 1.0;
    std::vector<fatek::PollItem> items;
    fatek::PollPlan plan;
    ros::Publisher pub;
    ros::WallTime due;
  };

  void worker();
  bool ensure_connected();
  void poll_io();
  void poll_group(Group& g);
  void fail(const std::string& what);
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
  void publish_signal(size_t i, bool on, const ros::Time& stamp);

  std::unique_ptr<fatek::Client> client_;
  std::string link_name_;
  std::vector<Group> groups_;
  std::vector<std::pair<std::string, Address>> signals_;
  std::vector<fatek::PollItem> io_items_;
  fatek::PollPlan io_plan_;
  double io_period_ = 0.1, max_backoff_ = 10.0;
  ros::WallTime io_due_;

  ros::Publisher io_pub_;
  std::vector<ros::Publisher> signal_pubs_;
  std::vector<ros::Publisher> stamped_pubs_;  // ~signals_stamped/<name>
  std::string frame_id_;                      // ~frame_id of every header
  std::vector<int> last_signals_;
  std::vector<ros::ServiceServer> services_;
  ros::Timer diag_timer_;
  diagnostic_updater::Updater updater_;

  std::mutex link_mu_;  // one transaction at a time on the half-duplex link
  std::mutex state_mu_;
  std::condition_variable cv_;
  bool stopping_ = false;
  bool connected_ = false;
  bool recover_ = false;
  std::string last_error_;
  uint64_t errors_ = 0, polls_ = 0, reconnects_ = 0;
  double latency_ms_ = 0, latency_max_ms_ = 0;
  std::thread worker_;
};

}  // namespace plc_cell
