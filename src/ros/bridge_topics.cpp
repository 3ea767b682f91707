#include "plc_cell/ros/bridge_topics.h"

#include <std_msgs/Bool.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include "plc_cell/IoState.h"
#include "plc_cell/Signal.h"
#include "plc_cell/core/error.h"
#include "plc_cell/ros/frame_id.h"

namespace plc_cell {

BridgeTopics::BridgeTopics(ros::NodeHandle& pnh, const std::vector<std::pair<std::string, Address>>& signals,
                           const std::vector<RegisterGroup>& groups)
    : groups_(groups) {
  frame_id_ = frame_id_param(pnh);
  io_pub_ = pnh.advertise<IoState>("io", 10);
  for (const auto& g : groups) group_pubs_.push_back(pnh.advertise<RegisterBlock>("registers/" + g.name, 10));
  for (const auto& s : signals) signal_pubs_.push_back(pnh.advertise<std_msgs::Bool>("signals/" + s.first, 1, true));
  for (const auto& s : signals) stamped_pubs_.push_back(pnh.advertise<Signal>("signals_stamped/" + s.first, 100, true));
  last_signals_.assign(signals.size(), -1);
}

void BridgeTopics::on_io(const IoResult& r) {
  if (!r.ok) return;  // counted in diagnostics
  IoState msg;
  msg.header.stamp = ros::Time::now();
  msg.header.frame_id = frame_id_;
  msg.run = r.run;
  msg.x.assign(r.x.begin(), r.x.end());
  msg.y.assign(r.y.begin(), r.y.end());
  io_pub_.publish(msg);
  for (size_t i = 0; i < r.signals.size() && i < last_signals_.size(); ++i) {
    const int now = int(r.signals[i]);
    if (now == last_signals_[i]) continue;  // latched topics: publish on change
    last_signals_[i] = now;
    publish_signal(i, now, msg.header.stamp);
  }
}

// The stamp is the poll's: when the bridge saw the change, not when the PLC made it.
void BridgeTopics::publish_signal(size_t i, bool on, const ros::Time& stamp) {
  std_msgs::Bool b;
  b.data = on;
  signal_pubs_[i].publish(b);
  Signal st;
  st.header.stamp = stamp;
  st.header.frame_id = frame_id_;
  st.data = on;
  stamped_pubs_[i].publish(st);
}

void BridgeTopics::on_group(const GroupResult& r) {
  if (!r.ok || r.group >= groups_.size()) return;
  const RegisterGroup& g = groups_[r.group];
  group_pubs_[r.group].publish(register_block(ros::Time::now(), frame_id_, g.name, g.text, r.values));
}

LinkParams read_link_params(ros::NodeHandle& pnh, int default_baud, const std::string& default_format) {
  LinkParams p;
  std::string port, format = default_format;
  int baud = default_baud;
  pnh.param<std::string>("tcp", p.tcp, "");
  pnh.param<std::string>("port", port, "");
  pnh.param<std::string>("format", format, format);
  pnh.param<std::string>("config", p.config, "");
  pnh.param("baud", baud, baud);
  pnh.param("retries", p.retries, p.retries);
  pnh.param("timeout", p.timeout_s, p.timeout_s);
  pnh.param("io_rate", p.io_rate_hz, p.io_rate_hz);
  pnh.param("max_backoff", p.max_backoff_s, p.max_backoff_s);
  // Checked here to name the parameters; the bus side checks the same bounds again.
  if (p.tcp.empty() == port.empty()) throw Error("give exactly one of ~tcp (HOST:PORT) or ~port (serial device)");
  if (!(p.io_rate_hz > 0 && p.io_rate_hz <= 100)) throw Error("~io_rate must be in (0, 100] Hz");
  if (!(p.timeout_s > 0)) throw Error("~timeout must be positive");
  if (!(p.max_backoff_s >= 0.1)) throw Error("~max_backoff must be at least 0.1 s (the first delay)");
  if (p.tcp.empty()) p.serial = port + ":" + std::to_string(baud) + ":" + format;
  return p;
}

std::vector<ros::ServiceServer> advertise_link_services(ros::NodeHandle& pnh, PolledLink& link,
                                                        std::function<void(bool)> set_run) {
  std::vector<ros::ServiceServer> out;
  PolledLink* l = &link;
  out.push_back(pnh.advertiseService<std_srvs::SetBool::Request, std_srvs::SetBool::Response>(
      "set_run_mode", [set_run](std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
        try {
          set_run(req.data);
          res.success = true;
          res.message = req.data ? "RUN" : "STOP";
        } catch (const std::exception& e) {
          res.success = false;
          res.message = e.what();
        }
        return true;
      }));
  out.push_back(advertise_recover(pnh, [l] {
    l->recover();
    return "reconnecting to " + l->describe();
  }));
  return out;
}

ros::ServiceServer advertise_recover(ros::NodeHandle& pnh, std::function<std::string()> recover) {
  return pnh.advertiseService<std_srvs::Trigger::Request, std_srvs::Trigger::Response>(
      "recover", [recover](std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
        res.message = recover();
        res.success = true;
        return true;
      });
}

ros::Timer start_diagnostics(ros::NodeHandle& nh, diagnostic_updater::Updater& updater, const std::string& hardware_id) {
  updater.setHardwareID(hardware_id);
  diagnostic_updater::Updater* u = &updater;
  return nh.createTimer(ros::Duration(1.0), [u](const ros::TimerEvent&) { u->update(); });
}

void diagnose_link(diagnostic_updater::DiagnosticStatusWrapper& stat, const PolledLink& link) {
  const LinkStatus s = link.status();
  const LinkHealth h = link_health(s);
  stat.summary(h.level == LinkLevel::Ok     ? diagnostic_msgs::DiagnosticStatus::OK
               : h.level == LinkLevel::Warn ? diagnostic_msgs::DiagnosticStatus::WARN
                                            : diagnostic_msgs::DiagnosticStatus::ERROR,
               h.message);
  stat.add("link", link.describe());
  stat.add("connected", s.connected);
  stat.add("last error", s.last_error);
  stat.add("errors", s.errors);
  stat.add("polls", s.polls);
  stat.add("reconnects", s.reconnects);
  stat.add("failed polls in a row", s.failed_polls_in_row);
  stat.add("I/O poll latency (ms)", s.latency_last_ms);
  stat.add("I/O poll latency max (ms)", s.latency_max_ms);
}

}  // namespace plc_cell
