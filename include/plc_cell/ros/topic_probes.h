#pragma once
// An extension's scenario probes read from plc_node's topics: the ROS side of its
// ProbeFacet (config/probe_facet.h) for the scenario_runner node, registered under the
// extension's name. The scenario target (scenario_ros_target.h) subscribes through it to the
// topics it reads, and asks it to check, read and drive the names of its families; so the
// target names no subsystem.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace scenario {

// What the target's connection to plc_node offers a side.
class TopicFeed {
 public:
  virtual ~TopicFeed() = default;
  virtual const std::string& node() const = 0;  // plc_node's resolved name
  virtual ros::NodeHandle& handle() = 0;
  // A message of topic, stamped stamp_ns, arrived: counted for the scan it completes and,
  // when it is of this case, stored with store() under the connection's lock.
  virtual void received(const std::string& topic, uint64_t stamp_ns, const std::function<void()>& store) = 0;
  // A publisher of an input to plc_node; connect_publisher() waits until plc_node hears it.
  virtual ros::Publisher advertise(ros::AdvertiseOptions options) = 0;
  virtual void connect_publisher(ros::Publisher* pub, const std::string& what) = 0;
  // The stamp of the next scan, for an input sent now (acknowledged before that scan).
  virtual ros::Time next_input_stamp() = 0;
};

// Subscribes topic through feed, storing each message of the case with store(msg).
template <class M>
ros::Subscriber keep(TopicFeed& feed, const std::string& topic, std::function<void(const M&)> store) {
  return feed.handle().subscribe<M>(topic, 1000, [&feed, topic, store](const typename M::ConstPtr& m) {
    feed.received(topic, m->header.stamp.toNSec(), [&] { store(*m); });
  });
}

class TopicProbes {
 public:
  virtual ~TopicProbes() = default;
  virtual std::vector<std::string> families() const = 0;
  // Subscribes topic (plc_node's, resolved) when this side reads it; false if it does not.
  virtual bool subscribe(TopicFeed& feed, const std::string& topic, ros::Subscriber* sub) = 0;
  // Once the topics are subscribed: waits for plc_node to hear this side's inputs.
  virtual void connect(TopicFeed& feed) { (void)feed; }
  // Why p cannot be read (writing false) or driven; has(private name): plc_node publishes it.
  virtual std::string check(const Probe& p, bool writing, const std::function<bool(const std::string&)>& has) const = 0;
  // Under the feed's lock: p as the last message of this case shows it.
  virtual Reading read(const std::string& node, const Probe& p) const = 0;
  // Throws Error saying why not.
  virtual void set(TopicFeed& feed, const Probe& p, const Value& v);
  // Under the feed's lock: a new case, no message yet.
  virtual void clear() = 0;
};

using TopicProbesFactory = std::function<std::unique_ptr<TopicProbes>()>;

// Registers the topic probes of extension while the object lives (a static in its file).
class TopicProbesRegistration {
 public:
  TopicProbesRegistration(std::string extension, TopicProbesFactory make);
  ~TopicProbesRegistration();
  TopicProbesRegistration(const TopicProbesRegistration&) = delete;
  TopicProbesRegistration& operator=(const TopicProbesRegistration&) = delete;

 private:
  std::string extension_;
};

// One of each registered side, in the order of the extensions' names.
std::vector<std::unique_ptr<TopicProbes>> registered_topic_probes();

}  // namespace scenario
}  // namespace plc_cell
