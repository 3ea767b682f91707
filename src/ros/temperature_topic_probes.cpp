// The modules' probes on plc_node (temp/module_probes.h on the cell in process):
// temperature.CHANNEL read from ~temperature/<channel> and driven in degC through
// ~temperature_inputs/<channel>; analog.CHANNEL has no topic (`plc_cell test` drives it).
#include <cmath>
#include <map>

#include <sensor_msgs/Temperature.h>

#include "plc_cell/core/error.h"
#include "plc_cell/ros/topic_probes.h"

namespace plc_cell {
namespace scenario {
namespace {

bool starts_with(const std::string& s, const std::string& p) { return s.compare(0, p.size(), p) == 0; }

class TemperatureTopicProbes : public TopicProbes {
 public:
  std::vector<std::string> families() const override { return {"temperature", "analog"}; }

  bool subscribe(TopicFeed& feed, const std::string& topic, ros::Subscriber* sub) override {
    const std::string rel = topic.substr(feed.node().size() + 1);
    if (!starts_with(rel, "temperature/")) return false;
    const std::string channel = rel.substr(std::string("temperature/").size());
    inputs_[channel] = feed.advertise(ros::AdvertiseOptions::create<sensor_msgs::Temperature>(
        feed.node() + "/temperature_inputs/" + channel, 1000, ros::SubscriberStatusCallback(),
        ros::SubscriberStatusCallback(), ros::VoidConstPtr(), nullptr));
    *sub = keep<sensor_msgs::Temperature>(
        feed, topic, [this, topic](const sensor_msgs::Temperature& m) { temperatures_[topic] = m.temperature; });
    return true;
  }

  void connect(TopicFeed& feed) override {
    for (auto& p : inputs_) feed.connect_publisher(&p.second, "a temperature channel's input");
  }

  std::string check(const Probe& p, bool writing, const std::function<bool(const std::string&)>& has) const override {
    if (p.family == "analog")
      return p.text + ": plc_node has no topic for analog input channels" +
             std::string(writing ? " and no way to set one" : "") + "; run this case with `plc_cell test`";
    if (!has("temperature/" + p.name))
      return p.text + ": plc_node publishes no ~temperature/" + p.name + " (no channel of that name in the cell)";
    return "";
  }

  Reading read(const std::string& node, const Probe& p) const override {
    Reading r;
    if (p.family != "temperature") {
      r.valid = false;
      r.text = "unreadable";
      return r;
    }
    const auto it = temperatures_.find(node + "/temperature/" + p.name);
    const double c = it == temperatures_.end() ? std::nan("") : it->second;
    r.valid = std::isfinite(c);  // NaN: a broken line
    r.number = r.valid ? c : 0;
    r.text = r.valid ? probe_number_text(std::round(c * 1000) / 1000) + " C" : "NaN (broken)";
    return r;
  }

  void set(TopicFeed& feed, const Probe& p, const Value& v) override {
    const auto it = inputs_.find(p.name);
    if (p.family != "temperature" || it == inputs_.end())
      throw Error(check(p, true, [this](const std::string&) { return false; }));
    if (v.has_unit && v.unit != "C")
      throw Error(p.text + ": " + v.text + ": plc_node's ~temperature_inputs/" + p.name +
                  " takes degrees C (a sensor's mV or ohm only with `plc_cell test`)");
    sensor_msgs::Temperature m;
    m.header.stamp = feed.next_input_stamp();
    m.temperature = v.number;
    it->second.publish(m);
  }

  void clear() override { temperatures_.clear(); }

 private:
  std::map<std::string, double> temperatures_;  // by topic
  std::map<std::string, ros::Publisher> inputs_;  // channel -> ~temperature_inputs/<channel>
};

const TopicProbesRegistration kModules("modules", [] { return std::make_unique<TemperatureTopicProbes>(); });

}  // namespace
}  // namespace scenario
}  // namespace plc_cell
