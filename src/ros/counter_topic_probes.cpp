// The counters' probes on plc_node (hsc/counter_probes.h on the cell in process):
// counter.NAME from ~counters/<name>, pulse.Xn.width, .period, .frequency from ~pulses/Xn.
#include <map>

#include "plc_cell/Counter.h"
#include "plc_cell/PulseMeasurement.h"
#include "plc_cell/ros/topic_probes.h"

namespace plc_cell {
namespace scenario {
namespace {

bool starts_with(const std::string& s, const std::string& p) { return s.compare(0, p.size(), p) == 0; }

class CounterTopicProbes : public TopicProbes {
 public:
  std::vector<std::string> families() const override { return {"counter", "pulse"}; }

  bool subscribe(TopicFeed& feed, const std::string& topic, ros::Subscriber* sub) override {
    const std::string rel = topic.substr(feed.node().size() + 1);
    if (starts_with(rel, "pulses/"))
      *sub = keep<PulseMeasurement>(feed, topic, [this, topic](const PulseMeasurement& m) { pulses_[topic] = m; });
    else if (starts_with(rel, "counters/"))
      *sub = keep<Counter>(feed, topic, [this, topic](const Counter& m) { counters_[topic] = m; });
    else
      return false;
    return true;
  }

  std::string check(const Probe& p, bool writing, const std::function<bool(const std::string&)>& has) const override {
    if (p.family == "counter") {
      if (writing) return p.text + ": plc_node has no topic or service that sets a counter in a scenario";
      if (!has("counters/" + p.name))
        return p.text + ": plc_node publishes no ~counters/" + p.name + " (no counter of that name in the cell)";
      return "";
    }
    if (writing) return p.text + ": a pulse measurement is read, not driven";
    if (!has("pulses/" + p.name))
      return p.text + ": plc_node publishes no ~pulses/" + p.name + " (the input is not measured in the cell)";
    return "";
  }

  Reading read(const std::string& node, const Probe& p) const override {
    Reading r;
    if (p.family == "counter") {
      const auto it = counters_.find(node + "/counters/" + p.name);
      r.number = it == counters_.end() ? 0 : double(it->second.count);
    } else {
      const auto it = pulses_.find(node + "/pulses/" + p.name);
      PulseMeasurement m;
      if (it != pulses_.end()) m = it->second;
      r.number = p.field == "width" ? m.width : p.field == "period" ? m.period : m.frequency;
    }
    r.text = probe_number_text(r.number);
    return r;
  }

  void clear() override {
    counters_.clear();
    pulses_.clear();
  }

 private:
  std::map<std::string, Counter> counters_;  // by topic
  std::map<std::string, PulseMeasurement> pulses_;
};

const TopicProbesRegistration kCounters("counters", [] { return std::make_unique<CounterTopicProbes>(); });

}  // namespace
}  // namespace scenario
}  // namespace plc_cell
