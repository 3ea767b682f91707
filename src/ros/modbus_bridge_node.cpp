#include "plc_cell/ros/modbus_bridge_node.h"

#include <std_msgs/Bool.h>
#include <std_msgs/Float32.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Int16.h>
#include <std_msgs/Int32.h>
#include <std_msgs/Int64.h>
#include <std_msgs/UInt16.h>
#include <std_msgs/UInt32.h>
#include <std_msgs/UInt64.h>

#include "plc_cell/core/error.h"
#include "plc_cell/ros/bridge_topics.h"
#include "plc_cell/ros/frame_id.h"

namespace plc_cell {

using modbus::Point;
using modbus::PointType;

namespace {

// A point with scale/offset publishes its engineering value as Float64; otherwise
// the std_msgs type of its wire type, exact for 64-bit integers.
bool scaled(const Point& p) { return p.scale != 1.0 || p.offset != 0.0; }

ros::Publisher advertise(ros::NodeHandle& nh, const std::string& topic, const Point& p) {
  if (scaled(p)) return nh.advertise<std_msgs::Float64>(topic, 10, true);
  switch (p.enc.type) {
    case PointType::Bool: return nh.advertise<std_msgs::Bool>(topic, 10, true);
    case PointType::Int16: return nh.advertise<std_msgs::Int16>(topic, 10, true);
    case PointType::UInt16: return nh.advertise<std_msgs::UInt16>(topic, 10, true);
    case PointType::Int32: return nh.advertise<std_msgs::Int32>(topic, 10, true);
    case PointType::UInt32: return nh.advertise<std_msgs::UInt32>(topic, 10, true);
    case PointType::Float32: return nh.advertise<std_msgs::Float32>(topic, 10, true);
    case PointType::Int64: return nh.advertise<std_msgs::Int64>(topic, 10, true);
    case PointType::UInt64: return nh.advertise<std_msgs::UInt64>(topic, 10, true);
    case PointType::Float64: return nh.advertise<std_msgs::Float64>(topic, 10, true);
  }
  return {};
}

template <typename M, typename V>
void send(ros::Publisher& pub, V v) {
  M m;
  m.data = v;
  pub.publish(m);
}

}  // namespace

ModbusBridgeNode::ModbusBridgeNode(ros::NodeHandle& nh, ros::NodeHandle& pnh) : updater_(nh, pnh, pnh.getNamespace()) {
  std::string path;
  if (!pnh.getParam("config", path)) throw Error("~config (the bridge YAML) is required");
  modbus::BridgeConfig cfg = modbus::load_bridge_config(path);
  frame_id_ = frame_id_param(pnh);
  for (const auto& d : cfg.devices) {
    points_.emplace_back();
    last_full_.emplace_back(d.groups.size(), ros::Time(0));
    block_pubs_.push_back(pnh.advertise<RegisterBlock>(d.name + "/blocks", 50));
    for (const auto& g : d.groups) {
      points_.back().emplace_back();
      for (const auto& p : g.points) {
        PointState st;
        st.pub = advertise(pnh, d.name + "/" + p.name, p);
        points_.back().back().push_back(st);
      }
    }
  }
  for (size_t d = 0; d < cfg.devices.size(); ++d)
    updater_.add(cfg.devices[d].name, [this, d](diagnostic_updater::DiagnosticStatusWrapper& s) { diagnose(d, s); });
  bridge_ = std::make_unique<modbus::Bridge>(std::move(cfg), [this](const modbus::GroupResult& r) { on_result(r); });
  // Not ~write: that name is plc_cell/WriteMemory (raw elements at an address) on plc_node
  // and fatek_bridge, while this one takes an engineering value for a named point.
  services_.push_back(pnh.advertiseService("write_point", &ModbusBridgeNode::on_write, this));
  services_.push_back(advertise_recover(pnh, [this] {
    bridge_->recover();
    return std::string("reconnecting every line now");
  }));
  diag_timer_ = start_diagnostics(nh, updater_, "modbus_bridge");
  bridge_->start();
}

ModbusBridgeNode::~ModbusBridgeNode() {
  if (bridge_) bridge_->stop();
}

void ModbusBridgeNode::publish_point(const Point& p, PointState& st, const modbus::Value& v, double eng) {
  if (scaled(p)) return send<std_msgs::Float64>(st.pub, eng);
  switch (p.enc.type) {
    case PointType::Bool: return send<std_msgs::Bool>(st.pub, v.raw != 0);
    case PointType::Int16: return send<std_msgs::Int16>(st.pub, int16_t(v.as_int64()));
    case PointType::UInt16: return send<std_msgs::UInt16>(st.pub, uint16_t(v.raw));
    case PointType::Int32: return send<std_msgs::Int32>(st.pub, int32_t(v.as_int64()));
    case PointType::UInt32: return send<std_msgs::UInt32>(st.pub, uint32_t(v.raw));
    case PointType::Float32: return send<std_msgs::Float32>(st.pub, float(v.as_double()));
    case PointType::Int64: return send<std_msgs::Int64>(st.pub, v.as_int64());
    case PointType::UInt64: return send<std_msgs::UInt64>(st.pub, v.raw);
    case PointType::Float64: return send<std_msgs::Float64>(st.pub, v.as_double());
  }
}

// Runs on the bridge's line threads.
void ModbusBridgeNode::on_result(const modbus::GroupResult& r) {
  if (!r.ok) return;  // counted in diagnostics
  const auto& dev = bridge_->config().devices[r.device];
  const auto& g = dev.groups[r.group];
  const ros::Time now = ros::Time::now();
  std::lock_guard<std::mutex> lk(mu_);
  const bool full = (now - last_full_[r.device][r.group]).toSec() >= g.publish_period_s;
  if (full) last_full_[r.device][r.group] = now;
  for (size_t i = 0; i < g.points.size(); ++i) {
    PointState& st = points_[r.device][r.group][i];
    if (!full && st.has && st.raw == r.values[i].raw) continue;  // on change, and periodically
    st.has = true;
    st.raw = r.values[i].raw;
    publish_point(g.points[i], st, r.values[i], r.engineering[i]);
  }
  for (size_t k = 0; k < r.reads.size(); ++k)
    block_pubs_[r.device].publish(register_block(
        now, frame_id_, g.name, std::string(modbus::table_name(r.reads[k].table)) + ":" + std::to_string(r.reads[k].address),
        r.blocks[k]));
}

bool ModbusBridgeNode::on_write(WritePoint::Request& req, WritePoint::Response& res) {
  try {
    bridge_->write(req.point, req.value);
    res.success = true;
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
  }
  return true;
}

void ModbusBridgeNode::diagnose(size_t d, diagnostic_updater::DiagnosticStatusWrapper& stat) {
  const modbus::DeviceStatus s = bridge_->status(d);
  const auto& dev = bridge_->config().devices[d];
  if (!s.connected) stat.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "disconnected: " + s.last_error);
  else if (!s.last_exception.empty()) stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "exception " + s.last_exception);
  else stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "connected");
  stat.add("endpoint", dev.tcp.empty() ? "rtu " + dev.rtu : "tcp " + dev.tcp);
  stat.add("unit", dev.unit);
  stat.add("connected", s.connected);
  stat.add("polls", s.polls);
  stat.add("writes", s.writes);
  stat.add("timeouts", s.timeouts);
  stat.add("exceptions", s.exceptions);
  stat.add("io errors", s.io_errors);
  stat.add("last exception", s.last_exception);
  stat.add("last error", s.last_error);
  stat.add("latency last (ms)", s.latency_last_ms);
  stat.add("latency avg (ms)", s.latency_n ? s.latency_sum_ms / double(s.latency_n) : 0.0);
  stat.add("latency max (ms)", s.latency_max_ms);
}

}  // namespace plc_cell
