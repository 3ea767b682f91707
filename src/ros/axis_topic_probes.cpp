// The axes' probes on plc_node (motion/axis_probes.h on the cell in process):
// axis.NAME.position, .frequency and .state from ~motion/<axis>/status.
#include <map>

#include "plc_cell/AxisStatus.h"
#include "plc_cell/motion/axis_probes.h"
#include "plc_cell/ros/topic_probes.h"

namespace plc_cell {
namespace scenario {
namespace {

bool starts_with(const std::string& s, const std::string& p) { return s.compare(0, p.size(), p) == 0; }
bool ends_with(const std::string& s, const std::string& p) {
  return s.size() >= p.size() && s.compare(s.size() - p.size(), p.size(), p) == 0;
}

class AxisTopicProbes : public TopicProbes {
 public:
  std::vector<std::string> families() const override { return {"axis"}; }

  bool subscribe(TopicFeed& feed, const std::string& topic, ros::Subscriber* sub) override {
    const std::string rel = topic.substr(feed.node().size() + 1);
    if (!starts_with(rel, "motion/") || !ends_with(rel, "/status")) return false;
    *sub = keep<AxisStatus>(feed, topic, [this, topic](const AxisStatus& m) { axes_[topic] = m; });
    return true;
  }

  std::string check(const Probe& p, bool writing, const std::function<bool(const std::string&)>& has) const override {
    if (writing) return p.text + ": an axis cannot be driven by a scenario step";
    if (!has("motion/" + p.name + "/status"))
      return p.text + ": plc_node publishes no ~motion/" + p.name + "/status (no axis of that name in the cell)";
    return "";
  }

  // As the cell in process reads it: pulses, Hz signed by the direction, and the state an
  // error code, else pulses going out, else idle.
  Reading read(const std::string& node, const Probe& p) const override {
    const auto it = axes_.find(node + "/motion/" + p.name + "/status");
    AxisStatus s;
    if (it != axes_.end()) s = it->second;
    return motion::axis_reading(p.field, s.pulses, s.frequency, s.error);
  }

  void clear() override { axes_.clear(); }

 private:
  std::map<std::string, AxisStatus> axes_;  // by topic
};

const TopicProbesRegistration kAxes("axes", [] { return std::make_unique<AxisTopicProbes>(); });

}  // namespace
}  // namespace scenario
}  // namespace plc_cell
