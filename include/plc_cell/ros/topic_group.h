#pragma once
// A set of plc_node topics published together at one rate from one copy of the cell's
// state (counters, axes, temperatures, a register group). The node, not the group,
// decides when and with what stamp: on a wall-clock timer stamped now in real time, and
// at scans of virtual time stamped with the scan, so a bag of every topic replays bit for
// bit (docs/plc-node.md "Stamps and virtual time").
#include <cstdint>
#include <memory>
#include <vector>

#include <ros/ros.h>

namespace plc_cell {

class TopicGroup {
 public:
  virtual ~TopicGroup() = default;
  // Hz of wall-clock time in real time, of virtual time in virtual time.
  virtual double rate_hz() const = 0;
  // Copies the state under the PLC lock, publishes after releasing it: a slow subscriber
  // never holds up a scan.
  virtual void publish(const ros::Time& stamp) = 0;
};

// When a group publishes in virtual time: at the first scan, then at the first scan at or
// after each later multiple of its period. A period that is a multiple of the scan
// period gives stamps exactly one period apart.
class VirtualRate {
 public:
  explicit VirtualRate(double rate_hz);
  bool due(uint64_t now_us);  // true once per period; the caller then publishes

 private:
  uint64_t period_us_, due_us_ = 0;
};

// plc_node's groups, in the order they were added.
class TopicGroups {
 public:
  void add(std::unique_ptr<TopicGroup> group);
  // Real time: one wall-clock timer per group from now on.
  void start_timers(ros::NodeHandle& nh);
  // Virtual time: called after the scan at now_us, PLC lock not held.
  void after_virtual_scan(uint64_t now_us);

 private:
  struct Entry {
    std::unique_ptr<TopicGroup> group;
    VirtualRate rate;
    ros::Timer timer;
  };
  std::vector<Entry> entries_;
};

}  // namespace plc_cell
