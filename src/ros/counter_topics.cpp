#include "plc_cell/ros/counter_topics.h"

#include <sstream>

#include <std_msgs/Float64.h>
#include <std_srvs/Trigger.h>

#include "plc_cell/Counter.h"
#include "plc_cell/CounterArray.h"
#include "plc_cell/PresetCounter.h"
#include "plc_cell/core/error.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/ros/extension_ros.h"
#include "plc_cell/ros/frame_id.h"
#include "plc_cell/ros/pulse_topics.h"

namespace plc_cell {
namespace {

// Under the PLC lock only.
hsc::HscUnit& unit(SoftCell& cell) { return *cell.get<hsc::HscUnit>(); }

// The counters extension on ROS: ~counters and ~pulses at ~counter_rate (0: the cell's
// counters.publish_rate).
const RosSideRegistration kCountersSide("counters", [](RosSideContext& c, TopicGroups* groups) {
  double rate = 0;
  c.pnh.param("counter_rate", rate, rate);
  groups->add(std::make_unique<CounterTopics>(c.pnh, c.cell, rate));
  groups->add(std::make_unique<PulseTopics>(c.pnh, c.cell, rate));
});

}  // namespace

CounterTopics::CounterTopics(ros::NodeHandle& pnh, SoftCell& cell, double rate_hz)
    : cell_(&cell), frame_id_(frame_id_param(pnh)) {
  const hsc::HscConfig cfg = cell_->plc().locked([&](ScanEngine&, Memory&) { return unit(*cell_).config(); });
  for (int n = 0; n < 8; ++n) {
    if (!cfg.counters[n].used) continue;
    numbers_.push_back(n);
    names_.push_back(cfg.counters[n].name);
  }
  if (rate_hz <= 0) rate_hz = cfg.publish_rate_hz;
  if (!(rate_hz > 0 && rate_hz <= 1000)) throw Error("~counter_rate must be in (0, 1000] Hz");
  rate_hz_ = rate_hz;
  // A cell with no counters has no ~counters topic: an empty array every period would
  // only suggest that counters are there but report nothing.
  if (!numbers_.empty()) all_pub_ = pnh.advertise<CounterArray>("counters", 10);
  for (size_t i = 0; i < numbers_.size(); ++i) {
    const int n = numbers_[i];
    const std::string base = "counters/" + names_[i];
    one_pubs_.push_back(pnh.advertise<Counter>(base, 10));
    services_.push_back(pnh.advertiseService<PresetCounter::Request, PresetCounter::Response>(
        base + "/preset", [this, n, i](PresetCounter::Request& req, PresetCounter::Response& res) {
          if (req.value < -2147483648ll || req.value > 4294967295ll) {
            res.success = false;
            res.message = names_[i] + ": value " + std::to_string(req.value) +
                          " out of range -2147483648..4294967295 (a 32-bit counter)";
            return true;
          }
          cell_->plc().locked([&](ScanEngine&, Memory&) {
            unit(*cell_).preset(n, req.value);
            return 0;
          });
          cell_->plc().commit();  // a retentive counter is on disk before the reply
          res.success = true;
          return true;
        }));
    services_.push_back(pnh.advertiseService<std_srvs::Trigger::Request, std_srvs::Trigger::Response>(
        base + "/clear", [this, n](std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
          cell_->plc().locked([&](ScanEngine&, Memory&) {
            unit(*cell_).preset(n, 0);
            return 0;
          });
          cell_->plc().commit();
          res.success = true;
          return true;
        }));
  }
  // A pulse source whose rate comes from a topic: an encoder wheel on a real axis, a
  // simulated spindle whose speed another node decides.
  for (const auto& s : cfg.sources) {
    const std::string name = s.name;
    subs_.push_back(pnh.subscribe<std_msgs::Float64>(
        "sources/" + name + "/rate", 10, [this, name](const std_msgs::Float64::ConstPtr& m) {
          cell_->plc().locked([&](ScanEngine&, Memory&) {
            unit(*cell_).set_source_rate(name, m->data);
            return 0;
          });
        }));
  }
}

std::string CounterTopics::layout(SoftCell& cell) const {
  std::ostringstream out;
  cell.plc().locked([&](ScanEngine&, Memory&) {
    const hsc::HscConfig& hc = unit(cell).config();
    for (int n = 0; n < 8; ++n)
      if (hc.counters[n].used) out << "counter " << n << ' ' << hc.counters[n].name << '\n';
    out << "counter rate " << hc.publish_rate_hz << '\n';
    return 0;
  });
  return out.str();
}

std::vector<std::string> CounterTopics::topics() const {
  std::vector<std::string> out;
  if (all_pub_) out.push_back(all_pub_.getTopic());
  for (const auto& p : one_pubs_) out.push_back(p.getTopic());
  return out;
}

void CounterTopics::publish(const ros::Time& stamp) {
  struct Value {
    int64_t count;
    double frequency;
  };
  if (numbers_.empty()) return;
  std::vector<Value> values(numbers_.size());
  cell_->plc().locked([&](ScanEngine&, Memory&) {
    for (size_t i = 0; i < numbers_.size(); ++i)
      values[i] = {unit(*cell_).count(numbers_[i]), unit(*cell_).frequency(numbers_[i])};
    return 0;
  });
  CounterArray all;
  all.header.stamp = stamp;
  all.header.frame_id = frame_id_;
  for (size_t i = 0; i < numbers_.size(); ++i) {
    Counter c;
    c.header = all.header;
    c.name = names_[i];
    c.number = static_cast<uint8_t>(numbers_[i]);
    c.count = values[i].count;
    c.frequency = values[i].frequency;
    all.counters.push_back(c);
  }
  all_pub_.publish(all);
  for (size_t i = 0; i < all.counters.size(); ++i) one_pubs_[i].publish(all.counters[i]);
}

}  // namespace plc_cell
