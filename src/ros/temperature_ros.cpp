#include "plc_cell/ros/temperature_ros.h"

#include <cmath>
#include <limits>

#include <sensor_msgs/Temperature.h>

#include "plc_cell/core/error.h"
#include "plc_cell/ros/frame_id.h"
#include "plc_cell/temp/loop_settings.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace {

struct Reading {
  int16_t raw = 0;
  bool installed = false, abnormal = false;
  bool all_read = false;  // the module set has read every channel once
};

// What the PLC itself sees: the reading registers and the abnormal / installed bits.
std::vector<Reading> readings(SoftCell& cell) {
  temp::TemperatureCell& tc = *cell.temperature();
  return cell.plc().locked([&](ScanEngine&, Memory& m) {
    const auto& cfg = tc.config();
    const size_t n = tc.channels().size();
    std::vector<Reading> r(n);
    const uint32_t inst = m.reg(Area::R, temp::treg::kInstalled) | uint32_t(m.reg(Area::R, temp::treg::kInstalled + 1)) << 16;
    const uint16_t* wr = m.words(cfg.working.area) + cfg.working.index;
    const uint32_t abn = wr[1] | uint32_t(wr[2]) << 16;
    for (size_t i = 0; i < n; ++i) {
      r[i].raw = int16_t(m.reg(cfg.readings.area, cfg.readings.index + uint32_t(i)));
      r[i].installed = inst >> i & 1u;
      r[i].abnormal = abn >> i & 1u;
      r[i].all_read = tc.all_read();
    }
    return r;
  });
}

}  // namespace

TemperatureRos::TemperatureRos(ros::NodeHandle& pnh, SoftCell& cell, diagnostic_updater::Updater& updater)
    : cell_(cell), frame_id_(frame_id_param(pnh)) {
  pnh.param("temperature_rate", rate_hz_, rate_hz_);
  if (!(rate_hz_ > 0 && rate_hz_ <= 100)) throw Error("~temperature_rate must be in (0, 100] Hz");
  const auto& chans = cell_.temperature()->channels();
  for (size_t i = 0; i < chans.size(); ++i) {
    if (chans[i].name.empty()) continue;
    channel_.push_back(i);
    pubs_.push_back(pnh.advertise<sensor_msgs::Temperature>("temperature/" + chans[i].name, 10));
  }
  const auto& mods = cell_.temperature()->config().modules;
  for (size_t k = 0; k < mods.size(); ++k)
    updater.add("temperature module " + std::to_string(k + 1) + " (FBs-" + temp::module_info(mods[k].kind).name + ")",
                [this, k](diagnostic_updater::DiagnosticStatusWrapper& s) { diagnose_module(k, s); });
  set_loop_ = pnh.advertiseService("set_pid_loop", &TemperatureRos::on_set_loop, this);
}

void TemperatureRos::publish(const ros::Time& stamp) {
  const auto r = readings(cell_);
  const temp::TemperatureCell& tc = *cell_.temperature();
  const bool f = tc.config().fahrenheit;
  for (size_t p = 0; p < pubs_.size(); ++p) {
    const size_t i = channel_[p];
    const temp::ChannelState& ch = tc.channels()[i];
    sensor_msgs::Temperature m;
    m.header.stamp = stamp;
    m.header.frame_id = frame_id_;
    // sensor_msgs/Temperature is in degC whatever the modules' unit.
    const double v = r[i].raw / 10.0;
    const double c = f ? (v - 32.0) * 5.0 / 9.0 : v;
    const bool broken = !r[i].installed || r[i].raw == temp::kLineBrokenValue;
    m.temperature = broken ? std::numeric_limits<double>::quiet_NaN() : c;
    // A reading rounded to a step q has variance q^2/12 (uniform rounding error).
    const double q = ch.resolution_c * (f ? 5.0 / 9.0 : 1.0);
    m.variance = q * q / 12.0;
    pubs_[p].publish(m);
  }
}

void TemperatureRos::diagnose_module(size_t k, diagnostic_updater::DiagnosticStatusWrapper& stat) {
  const auto r = readings(cell_);
  const temp::TemperatureCell& tc = *cell_.temperature();
  const bool ready = !r.empty() && r[0].all_read;
  std::string bad;
  int n = 0;
  for (size_t i = 0; i < tc.channels().size(); ++i) {
    if (tc.channels()[i].module != int(k)) continue;
    const auto& ch = tc.channels()[i];
    const std::string label = ch.name.empty() ? "ch" + std::to_string(n) : ch.name;
    std::string state = !r[i].installed ? "not installed"
                        : r[i].raw == temp::kLineBrokenValue ? "line broken"
                        : r[i].abnormal ? "out of range"
                                         : std::to_string(r[i].raw / 10.0);
    stat.add(label, state);
    if (r[i].installed && r[i].abnormal) bad += (bad.empty() ? "" : ", ") + label;
    ++n;
  }
  if (!ready) stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "first multiplexed scan not complete");
  else if (!bad.empty()) stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "sensor abnormal: " + bad);
  else stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "measuring");
}

bool TemperatureRos::on_set_loop(SetPidLoop::Request& req, SetPidLoop::Response& res) {
  const temp::LoopDef* loop = nullptr;
  for (const auto& l : cell_.temperature()->config().loops)
    if (l.name == req.loop) loop = &l;
  res.success = false;
  if (!loop) {
    res.message = "no loop '" + req.loop + "' in modules.temperature.loops";
    return true;
  }
  temp::LoopChange change;
  change.setpoint = req.setpoint;
  change.kc = req.kc, change.ki = req.ki, change.td = req.td;
  res.message = temp::check_loop_change(*loop, change, cell_.temperature()->config().fahrenheit);
  if (!res.message.empty()) return true;  // refused: nothing written
  cell_.plc().locked([&](ScanEngine&, Memory& m) {
    temp::apply_loop_change(*loop, change, m);
    return 0;
  });
  res.success = true;
  res.message = "ok";
  return true;
}

}  // namespace plc_cell
