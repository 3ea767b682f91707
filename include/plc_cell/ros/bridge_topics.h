#pragma once
// The ROS side every bridge to real devices shares (fatek_bridge, tri_bridge, modbus_bridge):
// the topics with plc_node's names and types, ~io, ~signals/<name>, ~signals_stamped/<name>
// (latched, on change) and ~registers/<group>, fed by the bus side's sinks
// (io/polled_link.h); the register blocks; ~recover; and the link's entries on /diagnostics.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "plc_cell/RegisterBlock.h"
#include "plc_cell/config/register_groups.h"
#include "plc_cell/io/polled_link.h"

namespace plc_cell {

class BridgeTopics {
 public:
  BridgeTopics(ros::NodeHandle& pnh, const std::vector<std::pair<std::string, Address>>& signals,
               const std::vector<RegisterGroup>& groups);
  // On the bus side's thread. Failed polls publish nothing (they count on /diagnostics).
  void on_io(const IoResult& r);
  void on_group(const GroupResult& r);
  // A bridge's sinks (its Sinks struct: io, group, error) that publish here and log each
  // failure as node (throttled).
  template <class Sinks>
  Sinks sinks(const std::string& node) {
    Sinks s;
    s.io = [this](const IoResult& r) { on_io(r); };
    s.group = [this](const GroupResult& r) { on_group(r); };
    s.error = [node](const std::string& what) { ROS_WARN_THROTTLE(5, "%s: %s", node.c_str(), what.c_str()); };
    return s;
  }

 private:
  void publish_signal(size_t i, bool on, const ros::Time& stamp);
  std::vector<RegisterGroup> groups_;
  ros::Publisher io_pub_;
  std::vector<ros::Publisher> group_pubs_;    // ~registers/<group>
  std::vector<ros::Publisher> signal_pubs_;   // ~signals/<name>
  std::vector<ros::Publisher> stamped_pubs_;  // ~signals_stamped/<name>
  std::string frame_id_;                      // ~frame_id of every header
  std::vector<int> last_signals_;             // -1 before the first poll; the bridge's thread only
};

// The link parameters every bridge node reads: ~tcp or ~port/~baud/~format, ~timeout,
// ~retries, ~io_rate, ~max_backoff and ~config. Throws Error naming a bad parameter.
struct LinkParams {
  std::string tcp;     // HOST:PORT, or
  std::string serial;  // DEVICE:BAUD:FORMAT from ~port, ~baud, ~format
  std::string config;  // YAML of signals and groups ("" = none)
  int retries = 1;
  double timeout_s = 0.5, io_rate_hz = 10.0, max_backoff_s = 10.0;
};
LinkParams read_link_params(ros::NodeHandle& pnh, int default_baud, const std::string& default_format);

// A bridge's config (fatek::BridgeConfig, tri::BridgeConfig) from ~config, with the link
// parameters.
template <class Cfg>
Cfg bridge_config(const LinkParams& lp, Cfg (*load)(const std::string&)) {
  Cfg cfg = lp.config.empty() ? Cfg{} : load(lp.config);
  cfg.tcp = lp.tcp;
  cfg.serial = lp.serial;
  cfg.timeout_s = lp.timeout_s;
  cfg.retries = lp.retries;
  cfg.io_rate_hz = lp.io_rate_hz;
  cfg.backoff_max_s = lp.max_backoff_s;
  return cfg;
}

// A block of registers as read at stamp: plc_cell/RegisterBlock, header.frame_id ~frame_id.
template <class Values>
RegisterBlock register_block(const ros::Time& stamp, const std::string& frame_id, const std::string& name,
                             const std::string& address, const Values& values) {
  RegisterBlock b;
  b.header.stamp = stamp;
  b.header.frame_id = frame_id;
  b.name = name;
  b.address = address;
  b.values.assign(values.begin(), values.end());
  return b;
}

// ~recover (std_srvs/Trigger): drop the link(s) and reconnect now; recover says to what.
ros::ServiceServer advertise_recover(ros::NodeHandle& pnh, std::function<std::string()> recover);

// A bridge's /diagnostics: hardware id, its entries added by the caller, updated every
// second by the returned timer (keep it as long as the updater).
ros::Timer start_diagnostics(ros::NodeHandle& nh, diagnostic_updater::Updater& updater, const std::string& hardware_id);

// ~set_run_mode (std_srvs/SetBool: RUN true, STOP false, through set_run) and ~recover
// (std_srvs/Trigger: drop the link and reconnect now). link must outlive the servers.
std::vector<ros::ServiceServer> advertise_link_services(ros::NodeHandle& pnh, PolledLink& link,
                                                        std::function<void(bool)> set_run);

// The link's state on /diagnostics: connected or why not, errors, polls, reconnects, latency.
void diagnose_link(diagnostic_updater::DiagnosticStatusWrapper& stat, const PolledLink& link);

}  // namespace plc_cell
