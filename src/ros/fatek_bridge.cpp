#include "plc_cell/ros/fatek_bridge.h"

#include <std_msgs/Bool.h>

#include "plc_cell/IoState.h"
#include "plc_cell/RegisterBlock.h"
#include "plc_cell/Signal.h"
#include "plc_cell/core/error.h"
#include "plc_cell/ros/frame_id.h"

namespace plc_cell {

FatekBridge::FatekBridge(ros::NodeHandle& nh, ros::NodeHandle& pnh) : updater_(nh, pnh) {
  std::string tcp, port, format = "7E1", config;
  int baud = 9600, station = 1, retries = 1;
  double timeout = 0.5, io_rate = 10.0, max_backoff = 10.0;
  pnh.param<std::string>("tcp", tcp, "");
  pnh.param<std::string>("port", port, "");
  pnh.param<std::string>("format", format, format);
  pnh.param<std::string>("config", config, "");
  pnh.param("baud", baud, baud);
  pnh.param("station", station, station);
  pnh.param("retries", retries, retries);
  pnh.param("timeout", timeout, timeout);
  pnh.param("io_rate", io_rate, io_rate);
  pnh.param("max_backoff", max_backoff, max_backoff);
  // Checked here to name the parameters; the bus side checks the same bounds again.
  if (tcp.empty() == port.empty()) throw Error("give exactly one of ~tcp (HOST:PORT) or ~port (serial device)");
  if (station < 1 || station > 254) throw Error("~station must be 1..254");
  if (!(io_rate > 0 && io_rate <= 100)) throw Error("~io_rate must be in (0, 100] Hz");
  if (!(timeout > 0)) throw Error("~timeout must be positive");
  if (!(max_backoff >= 0.1)) throw Error("~max_backoff must be at least 0.1 s (the first delay)");

  fatek::BridgeConfig cfg = config.empty() ? fatek::BridgeConfig{} : fatek::load_bridge_config(config);
  cfg.tcp = tcp;
  if (tcp.empty()) cfg.serial = port + ":" + std::to_string(baud) + ":" + format;
  cfg.station = station;
  cfg.timeout_s = timeout;
  cfg.retries = retries;
  cfg.io_rate_hz = io_rate;
  cfg.backoff_max_s = max_backoff;

  frame_id_ = frame_id_param(pnh);
  io_pub_ = pnh.advertise<IoState>("io", 10);
  for (const auto& g : cfg.groups) group_pubs_.push_back(pnh.advertise<RegisterBlock>("registers/" + g.name, 10));
  for (const auto& s : cfg.signals) signal_pubs_.push_back(pnh.advertise<std_msgs::Bool>("signals/" + s.first, 1, true));
  for (const auto& s : cfg.signals)
    stamped_pubs_.push_back(pnh.advertise<Signal>("signals_stamped/" + s.first, 100, true));
  last_signals_.assign(cfg.signals.size(), -1);

  fatek::Bridge::Sinks sinks;
  sinks.io = [this](const fatek::IoResult& r) { on_io(r); };
  sinks.group = [this](const fatek::GroupResult& r) { on_group(r); };
  sinks.error = [](const std::string& what) { ROS_WARN_THROTTLE(5, "fatek_bridge: %s", what.c_str()); };
  bridge_ = std::make_unique<fatek::Bridge>(std::move(cfg), std::move(sinks));

  services_ = advertise_memory_services(pnh, *this);
  services_.push_back(pnh.advertiseService("set_run_mode", &FatekBridge::on_run, this));
  services_.push_back(pnh.advertiseService("recover", &FatekBridge::on_recover, this));
  updater_.setHardwareID("fatek/" + bridge_->describe());
  updater_.add("link", this, &FatekBridge::diagnose);
  diag_timer_ = nh.createTimer(ros::Duration(1.0), [this](const ros::TimerEvent&) { updater_.update(); });
  bridge_->start();
  ROS_INFO("fatek_bridge: %s, %zu group(s), %zu signal(s), I/O image %zu frame(s) per poll",
           bridge_->describe().c_str(), bridge_->config().groups.size(), bridge_->config().signals.size(),
           bridge_->io_frames());
}

FatekBridge::~FatekBridge() {
  if (bridge_) bridge_->stop();  // before the publishers its sinks reach go
}

// Runs on the bridge's thread.
void FatekBridge::on_io(const fatek::IoResult& r) {
  if (!r.ok) return;  // counted in diagnostics
  IoState msg;
  msg.header.stamp = ros::Time::now();
  msg.header.frame_id = frame_id_;
  msg.run = r.run;
  msg.x.assign(r.x.begin(), r.x.end());
  msg.y.assign(r.y.begin(), r.y.end());
  io_pub_.publish(msg);
  for (size_t i = 0; i < r.signals.size(); ++i) {
    const int now = int(r.signals[i]);
    if (now == last_signals_[i]) continue;  // latched topics: publish on change
    last_signals_[i] = now;
    publish_signal(i, now, msg.header.stamp);
  }
}

// The stamp is the poll's: when the bridge saw the change, not when the PLC made it.
void FatekBridge::publish_signal(size_t i, bool on, const ros::Time& stamp) {
  std_msgs::Bool b;
  b.data = on;
  signal_pubs_[i].publish(b);
  Signal st;
  st.header.stamp = stamp;
  st.header.frame_id = frame_id_;
  st.data = on;
  stamped_pubs_[i].publish(st);
}

void FatekBridge::on_group(const fatek::GroupResult& r) {
  if (!r.ok) return;
  const RegisterGroup& g = bridge_->config().groups[r.group];
  RegisterBlock msg;
  msg.header.stamp = ros::Time::now();
  msg.header.frame_id = frame_id_;
  msg.name = g.name;
  msg.address = g.text;
  msg.values.assign(r.values.begin(), r.values.end());
  group_pubs_[r.group].publish(msg);
}

void FatekBridge::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  const fatek::LinkStatus s = bridge_->status();
  if (s.connected) stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "connected");
  else stat.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "disconnected: " + s.last_error);
  stat.add("link", bridge_->describe());
  stat.add("connected", s.connected);
  stat.add("last error", s.last_error);
  stat.add("errors", s.errors);
  stat.add("polls", s.polls);
  stat.add("reconnects", s.reconnects);
  stat.add("I/O poll latency (ms)", s.latency_last_ms);
  stat.add("I/O poll latency max (ms)", s.latency_max_ms);
}

bool FatekBridge::on_run(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
  try {
    bridge_->set_run(req.data);
    res.success = true;
    res.message = req.data ? "RUN" : "STOP";
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
  }
  return true;
}

bool FatekBridge::on_recover(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  bridge_->recover();
  res.success = true;
  res.message = "reconnecting to " + bridge_->describe();
  return true;
}

}  // namespace plc_cell
