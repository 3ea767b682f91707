#include "plc_cell/ros/fatek_bridge.h"

#include <yaml-cpp/yaml.h>

#include <std_msgs/Bool.h>

#include "plc_cell/IoState.h"
#include "plc_cell/RegisterBlock.h"
#include "plc_cell/Signal.h"
#include "plc_cell/config/register_groups.h"
#include "plc_cell/core/error.h"
#include "plc_cell/io/backoff.h"
#include "plc_cell/ros/frame_id.h"

namespace plc_cell {

FatekBridge::FatekBridge(ros::NodeHandle& nh, ros::NodeHandle& pnh) : updater_(nh, pnh) {
  std::string tcp, port, format = "7E1", config;
  int baud = 9600, station = 1, retries = 1;
  double timeout = 0.5, io_rate = 10.0;
  pnh.param<std::string>("tcp", tcp, "");
  pnh.param<std::string>("port", port, "");
  pnh.param<std::string>("format", format, format);
  pnh.param<std::string>("config", config, "");
  pnh.param("baud", baud, baud);
  pnh.param("station", station, station);
  pnh.param("retries", retries, retries);
  pnh.param("timeout", timeout, timeout);
  pnh.param("io_rate", io_rate, io_rate);
  pnh.param("max_backoff", max_backoff_, max_backoff_);
  if (tcp.empty() == port.empty()) throw Error("give exactly one of ~tcp (HOST:PORT) or ~port (serial device)");
  if (station < 1 || station > 254) throw Error("~station must be 1..254");
  if (!(io_rate > 0 && io_rate <= 100)) throw Error("~io_rate must be in (0, 100] Hz");
  if (!(timeout > 0)) throw Error("~timeout must be positive");
  io_period_ = 1.0 / io_rate;

  fatek::ClientOptions co;
  co.station = station;
  co.timeout_ms = int(timeout * 1000);
  co.retries = retries;
  std::unique_ptr<fatek::Transport> t;
  if (!tcp.empty()) {
    t = fatek::tcp_transport(tcp);
  } else {
    const SerialSettings s = parse_serial_settings(port + ":" + std::to_string(baud) + ":" + format);
    t = fatek::serial_transport(s);
  }
  link_name_ = t->describe() + " station " + std::to_string(station);
  client_ = std::make_unique<fatek::Client>(std::move(t), co);

  // Config: signals (name -> discrete) and poll groups (name, rate, points).
  if (!config.empty()) {
    YAML::Node doc = YamlReader::load_file(config);
    if (doc["fatek_bridge"]) doc = doc["fatek_bridge"];
    const YamlReader r(config);
    r.only(doc, "", {"signals", "groups"});
    if (const auto sig = doc["signals"]) signals_ = r.discretes(sig, "signals");
    if (doc["groups"]) {
      for (auto& rg : parse_register_groups(doc["groups"], "groups", r)) {
        Group grp;
        grp.name = rg.name;
        grp.text = rg.text;
        grp.period = 1.0 / rg.rate_hz;
        grp.items = std::move(rg.spans);
        grp.plan = fatek::plan_poll(grp.items);
        grp.pub = pnh.advertise<RegisterBlock>("registers/" + grp.name, 10);
        groups_.push_back(std::move(grp));
      }
    }
  }
  // The I/O image: WX0..WX240 and WY0..WY240 (one 48 frame of weight 32) plus signals.
  io_items_.push_back({parse_address("WX0"), 16});
  io_items_.push_back({parse_address("WY0"), 16});
  for (const auto& s : signals_) io_items_.push_back({s.second, 1});
  io_plan_ = fatek::plan_poll(io_items_);

  frame_id_ = frame_id_param(pnh);
  io_pub_ = pnh.advertise<IoState>("io", 10);
  for (const auto& s : signals_) signal_pubs_.push_back(pnh.advertise<std_msgs::Bool>("signals/" + s.first, 1, true));
  for (const auto& s : signals_)
    stamped_pubs_.push_back(pnh.advertise<Signal>("signals_stamped/" + s.first, 100, true));
  last_signals_.assign(signals_.size(), -1);
  services_ = advertise_memory_services(pnh, *this);
  services_.push_back(pnh.advertiseService("set_run_mode", &FatekBridge::on_run, this));
  services_.push_back(pnh.advertiseService("recover", &FatekBridge::on_recover, this));

  updater_.setHardwareID("fatek/" + link_name_);
  updater_.add("link", this, &FatekBridge::diagnose);
  diag_timer_ = nh.createTimer(ros::Duration(1.0), [this](const ros::TimerEvent&) { updater_.update(); });
  worker_ = std::thread([this] { worker(); });
  ROS_INFO("fatek_bridge: %s, %zu group(s), %zu signal(s), I/O image %zu frame(s) per poll", link_name_.c_str(),
           groups_.size(), signals_.size(), io_plan_.requests.size() + 1);
}

FatekBridge::~FatekBridge() {
  {
    std::lock_guard<std::mutex> lk(state_mu_);
    stopping_ = true;
  }
  cv_.notify_all();
  if (worker_.joinable()) worker_.join();
}

void FatekBridge::fail(const std::string& what) {
  ROS_WARN_THROTTLE(5, "fatek_bridge: %s", what.c_str());
  std::lock_guard<std::mutex> lk(state_mu_);
  last_error_ = what;
  ++errors_;
}

bool FatekBridge::ensure_connected() {
  std::lock_guard<std::mutex> lk(link_mu_);
  if (client_->transport().is_open()) return true;
  try {
    client_->transport().open();
    client_->loopback("PLC");  // proves a slave answers at this station
    std::lock_guard<std::mutex> lk2(state_mu_);
    connected_ = true;
    ++reconnects_;
    return true;
  } catch (const std::exception& e) {
    client_->transport().close();
    {
      std::lock_guard<std::mutex> lk2(state_mu_);
      connected_ = false;
    }
    fail(std::string("connect: ") + e.what());
    return false;
  }
}

void FatekBridge::poll_io() {
  fatek::PlcStatus st;
  std::vector<std::vector<uint32_t>> v;
  {
    std::lock_guard<std::mutex> lk(link_mu_);
    const auto t0 = ros::WallTime::now();
    st = client_->status();
    v = fatek::run_poll(*client_, io_items_, io_plan_);
    const double ms = (ros::WallTime::now() - t0).toSec() * 1e3;
    std::lock_guard<std::mutex> lk2(state_mu_);
    latency_ms_ = ms;
    latency_max_ms_ = std::max(latency_max_ms_, ms);
    ++polls_;
  }
  IoState msg;
  msg.header.stamp = ros::Time::now();
  msg.header.frame_id = frame_id_;
  msg.run = st.run;
  msg.x.resize(256);
  msg.y.resize(256);
  for (uint32_t i = 0; i < 256; ++i) {
    msg.x[i] = (v[0][i / 16] >> (i % 16)) & 1;
    msg.y[i] = (v[1][i / 16] >> (i % 16)) & 1;
  }
  io_pub_.publish(msg);
  for (size_t i = 0; i < signals_.size(); ++i) {
    const int now = int(v[2 + i][0] != 0);
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

void FatekBridge::poll_group(Group& g) {
  std::vector<std::vector<uint32_t>> v;
  {
    std::lock_guard<std::mutex> lk(link_mu_);
    v = fatek::run_poll(*client_, g.items, g.plan);
  }
  RegisterBlock msg;
  msg.header.stamp = ros::Time::now();
  msg.header.frame_id = frame_id_;
  msg.name = g.name;
  msg.address = g.text;
  for (const auto& item : v)
    for (uint32_t x : item) msg.values.push_back(x);
  g.pub.publish(msg);
}

void FatekBridge::worker() {
  Backoff backoff(0.1, max_backoff_);
  io_due_ = ros::WallTime::now();
  for (auto& g : groups_) g.due = io_due_;
  for (;;) {
    {
      std::unique_lock<std::mutex> lk(state_mu_);
      if (stopping_) return;
      if (recover_) {
        recover_ = false;
        backoff.reset();
      }
    }
    if (!ensure_connected()) {
      std::unique_lock<std::mutex> lk(state_mu_);
      cv_.wait_for(lk, std::chrono::duration<double>(backoff.failed()), [this] { return stopping_ || recover_; });
      continue;
    }
    backoff.reset();
    try {
      const auto now = ros::WallTime::now();
      if (now >= io_due_) {
        poll_io();
        io_due_ += ros::WallDuration(io_period_);
        if (io_due_ < now) io_due_ = now + ros::WallDuration(io_period_);
      }
      for (auto& g : groups_) {
        if (ros::WallTime::now() < g.due) continue;
        poll_group(g);
        g.due += ros::WallDuration(g.period);
        if (g.due < now) g.due = now + ros::WallDuration(g.period);
      }
    } catch (const fatek::CommError& e) {
      fail(e.what());
      std::lock_guard<std::mutex> lk(link_mu_);
      client_->transport().close();  // reconnect (with back-off) on the next turn
      std::lock_guard<std::mutex> lk2(state_mu_);
      connected_ = false;
    } catch (const std::exception& e) {
      fail(e.what());  // a PLC error code for one group: keep the link
    }
    ros::WallTime next = io_due_;
    for (const auto& g : groups_) next = std::min(next, g.due);
    std::unique_lock<std::mutex> lk(state_mu_);
    const double wait = (next - ros::WallTime::now()).toSec();
    if (wait > 0) cv_.wait_for(lk, std::chrono::duration<double>(wait), [this] { return stopping_ || recover_; });
  }
}

void FatekBridge::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  std::lock_guard<std::mutex> lk(state_mu_);
  if (connected_) stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "connected");
  else stat.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "disconnected: " + last_error_);
  stat.add("link", link_name_);
  stat.add("connected", connected_);
  stat.add("last error", last_error_);
  stat.add("errors", errors_);
  stat.add("polls", polls_);
  stat.add("reconnects", reconnects_);
  stat.add("I/O poll latency (ms)", latency_ms_);
  stat.add("I/O poll latency max (ms)", latency_max_ms_);
}

bool FatekBridge::on_run(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
  try {
    std::lock_guard<std::mutex> lk(link_mu_);
    client_->set_run(req.data);
    res.success = true;
    res.message = req.data ? "RUN" : "STOP";
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
  }
  return true;
}

bool FatekBridge::on_recover(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  {
    std::lock_guard<std::mutex> lk(link_mu_);
    client_->transport().close();
  }
  {
    std::lock_guard<std::mutex> lk(state_mu_);
    connected_ = false;
    recover_ = true;
    last_error_.clear();
  }
  cv_.notify_all();
  res.success = true;
  res.message = "reconnecting to " + link_name_;
  return true;
}

}  // namespace plc_cell
