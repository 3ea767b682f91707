#include "plc_cell/ros/pulse_topics.h"

#include "plc_cell/PulseMeasurement.h"
#include "plc_cell/core/error.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/ros/frame_id.h"

namespace plc_cell {

PulseTopics::PulseTopics(ros::NodeHandle& pnh, SoftCell& cell, double rate_hz)
    : cell_(&cell), frame_id_(frame_id_param(pnh)) {
  const hsc::HscConfig cfg = cell_->plc().locked([&](ScanEngine&, Memory&) { return cell_->get<hsc::HscUnit>()->config(); });
  if (rate_hz <= 0) rate_hz = cfg.publish_rate_hz;
  if (!(rate_hz > 0 && rate_hz <= 1000)) throw Error("~counter_rate must be in (0, 1000] Hz");
  rate_hz_ = rate_hz;
  inputs_ = cfg.pulse.inputs;
  for (int n : cfg.pulse.counter_of) counters_.push_back(cfg.counters[n].name);
  unit_ = cfg.pulse.unit();
  tenths_ = cfg.pulse.tenths;
  for (int x : inputs_) pubs_.push_back(pnh.advertise<PulseMeasurement>("pulses/X" + std::to_string(x), 10));
}

std::string PulseTopics::layout(SoftCell& cell) const {
  std::string out;
  cell.plc().locked([&](ScanEngine&, Memory&) {
    const hsc::HscConfig& hc = cell.get<hsc::HscUnit>()->config();
    for (int x : hc.pulse.inputs) out += "pulse X" + std::to_string(x) + ' ' + hc.pulse.unit() + '\n';
    return 0;
  });
  return out;
}

std::vector<std::string> PulseTopics::topics() const {
  std::vector<std::string> out;
  for (const auto& p : pubs_) out.push_back(p.getTopic());
  return out;
}

void PulseTopics::publish(const ros::Time& stamp) {
  if (inputs_.empty()) return;
  std::vector<hsc::PulseReading> values(inputs_.size());
  cell_->plc().locked([&](ScanEngine&, Memory&) {
    for (size_t i = 0; i < inputs_.size(); ++i) values[i] = cell_->get<hsc::HscUnit>()->pulse(inputs_[i]);
    return 0;
  });
  const double scale = tenths_ ? 100.0 : 1000.0;  // ns per unit
  for (size_t i = 0; i < inputs_.size(); ++i) {
    PulseMeasurement m;
    m.header.stamp = stamp;
    m.header.frame_id = frame_id_;
    m.name = "X" + std::to_string(inputs_[i]);
    m.input = static_cast<uint8_t>(inputs_[i]);
    m.counter = counters_[i];
    m.width = double(values[i].width_ns) / scale;
    m.period = double(values[i].period_ns) / scale;
    m.frequency = values[i].frequency_hz;
    m.unit = unit_;
    pubs_[i].publish(m);
  }
}

}  // namespace plc_cell
