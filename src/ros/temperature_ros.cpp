#include "plc_cell/ros/temperature_ros.h"

#include <sensor_msgs/Temperature.h>

#include "plc_cell/core/error.h"
#include "plc_cell/ros/extension_ros.h"
#include "plc_cell/ros/frame_id.h"
#include "plc_cell/temp/loop_settings.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace {

// What the PLC itself sees (temp::TemperatureCell::readings), copied under the lock.
struct Readings {
  std::vector<temp::ChannelReading> channels;
  bool all_read = false;  // the module set has read every channel once
};

Readings readings(SoftCell& cell) {
  const temp::TemperatureCell& tc = *cell.get<temp::TemperatureCell>();
  return cell.plc().locked([&](ScanEngine&, Memory& m) { return Readings{tc.readings(m), tc.all_read()}; });
}

// The modules extension on ROS: a cell without temperature modules has none of its topics,
// yet the group is there, so that ~reset sees modules appear in the cell's files (layout).
const RosSideRegistration kModulesSide("modules", [](RosSideContext& c, TopicGroups* groups) {
  groups->add(std::make_unique<TemperatureRos>(c.pnh, c.cell, c.updater, c.inputs));
});

}  // namespace

TemperatureRos::TemperatureRos(ros::NodeHandle& pnh, SoftCell& cell, diagnostic_updater::Updater& updater,
                               StampedInputs& inputs)
    : cell_(&cell), frame_id_(frame_id_param(pnh)) {
  const temp::TemperatureCell* tc = cell_->get<temp::TemperatureCell>();
  if (!tc) return;
  pnh.param("temperature_rate", rate_hz_, rate_hz_);
  if (!(rate_hz_ > 0 && rate_hz_ <= 100)) throw Error("~temperature_rate must be in (0, 100] Hz");
  const auto& chans = tc->channels();
  for (size_t i = 0; i < chans.size(); ++i) {
    if (chans[i].name.empty()) continue;
    channel_.push_back(i);
    pubs_.push_back(pnh.advertise<sensor_msgs::Temperature>("temperature/" + chans[i].name, 10));
    // What the channel's sensor measures from the stamp on, in degC whatever the sensor.
    input_subs_.push_back(pnh.subscribe<sensor_msgs::Temperature>(
        "temperature_inputs/" + chans[i].name, 100, [this, i, &inputs](const sensor_msgs::Temperature::ConstPtr& m) {
          const double celsius = m->temperature;
          inputs.apply_at(m->header.stamp.toNSec() / 1000, [this, i, celsius](ScanEngine&) {
            std::string why;
            if (!cell_->get<temp::TemperatureCell>()->drive_channel(i, temp::Quantity{celsius, temp::Unit::Celsius}, &why))
              ROS_WARN("plc_node: ~temperature_inputs: %s", why.c_str());
          });
        }));
  }
  const auto& mods = tc->config().modules;
  for (size_t k = 0; k < mods.size(); ++k)
    updater.add("temperature module " + std::to_string(k + 1) + " (FBs-" + temp::module_info(mods[k].kind).name + ")",
                [this, k](diagnostic_updater::DiagnosticStatusWrapper& s) { diagnose_module(k, s); });
  set_loop_ = pnh.advertiseService("set_pid_loop", &TemperatureRos::on_set_loop, this);
}

std::string TemperatureRos::layout(SoftCell& cell) const {
  const temp::TemperatureCell* tc = cell.get<temp::TemperatureCell>();
  if (!tc) return "";
  std::string out;
  for (const auto& ch : tc->channels()) out += "channel " + ch.name + '\n';
  return out + "modules " + std::to_string(tc->config().modules.size()) + '\n';
}

std::vector<std::string> TemperatureRos::topics() const {
  std::vector<std::string> out;
  for (const auto& p : pubs_) out.push_back(p.getTopic());
  return out;
}

void TemperatureRos::publish(const ros::Time& stamp) {
  if (pubs_.empty()) return;
  const auto r = readings(*cell_);
  for (size_t p = 0; p < pubs_.size(); ++p) {
    const temp::ChannelReading& c = r.channels[channel_[p]];
    sensor_msgs::Temperature m;  // degC whatever the modules' unit; NaN while broken
    m.header.stamp = stamp;
    m.header.frame_id = frame_id_;
    m.temperature = c.celsius;
    m.variance = c.variance_c2;
    pubs_[p].publish(m);
  }
}

void TemperatureRos::diagnose_module(size_t k, diagnostic_updater::DiagnosticStatusWrapper& stat) {
  const auto r = readings(*cell_);
  const temp::TemperatureCell& tc = *cell_->get<temp::TemperatureCell>();
  std::string bad;
  int n = 0;
  for (size_t i = 0; i < tc.channels().size(); ++i) {
    if (tc.channels()[i].module != int(k)) continue;
    const auto& ch = tc.channels()[i];
    const std::string label = ch.name.empty() ? "ch" + std::to_string(n) : ch.name;
    stat.add(label, r.channels[i].state());
    if (r.channels[i].installed && r.channels[i].abnormal) bad += (bad.empty() ? "" : ", ") + label;
    ++n;
  }
  if (!r.all_read) stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "first multiplexed scan not complete");
  else if (!bad.empty()) stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "sensor abnormal: " + bad);
  else stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "measuring");
}

bool TemperatureRos::on_set_loop(SetPidLoop::Request& req, SetPidLoop::Response& res) {
  const temp::LoopDef* loop = nullptr;
  for (const auto& l : cell_->get<temp::TemperatureCell>()->config().loops)
    if (l.name == req.loop) loop = &l;
  res.success = false;
  if (!loop) {
    res.message = "no loop '" + req.loop + "' in modules.temperature.loops";
    return true;
  }
  temp::LoopChange change;
  change.setpoint = req.setpoint;
  change.kc = req.kc, change.ki = req.ki, change.td = req.td;
  res.message = temp::check_loop_change(*loop, change, cell_->get<temp::TemperatureCell>()->config().fahrenheit);
  if (!res.message.empty()) return true;  // refused: nothing written
  cell_->plc().locked([&](ScanEngine&, Memory& m) {
    temp::apply_loop_change(*loop, change, m);
    return 0;
  });
  res.success = true;
  res.message = "ok";
  return true;
}

}  // namespace plc_cell
