#pragma once
// A set of plc_node topics published together at one rate from one copy of the cell's
// state (counters, axes, temperatures, a register group). The node, not the group,
// decides when and with what stamp: on a wall-clock timer stamped now in real time, and
// at scans of virtual time stamped with the scan, so a bag of every topic replays bit for
// bit (docs/plc-node.md "Stamps and virtual time").
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>

namespace plc_cell {

class SoftCell;

class TopicGroup {
 public:
  virtual ~TopicGroup() = default;
  // Hz of wall-clock time in real time, of virtual time in virtual time.
  virtual double rate_hz() const = 0;
  // Copies the state under the PLC lock, publishes after releasing it: a slow subscriber
  // never holds up a scan.
  virtual void publish(const ros::Time& stamp) = 0;
  // The topics publish() puts one message on each (resolved names): what
  // ~virtual_time/scanned counts.
  virtual std::vector<std::string> topics() const = 0;
  // From now on, the group reads this cell (plc_node's ~reset): one built from the same
  // files, so with the same counters, axes, channels and groups.
  virtual void rebind(SoftCell& cell) = 0;
  // What the group's topics are made from in cell (names, numbers, units, rates), one line
  // each: a fresh cell must give the same for ~reset to keep the topics.
  virtual std::string layout(SoftCell& cell) const {
    (void)cell;
    return "";
  }
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
  // Virtual time: called after the scan at now_us, PLC lock not held. every_scan: each
  // group at every scan, not at its rate.
  void after_virtual_scan(uint64_t now_us, bool every_scan = false);
  // After the scan at now_us, whatever the driver (PLC lock not held): each group due then
  // (every_scan: every group) is counted and handed to run, which publishes it with stamp
  // now or on another thread.
  void after_scan(uint64_t now_us, bool every_scan, const ros::Time& stamp,
                  const std::function<void(std::function<void()>)>& run);
  // Virtual time: every group's topics, each with the messages published on it since the
  // start or the last restart().
  void count_published(std::vector<std::string>* topics, std::vector<uint64_t>* counts) const;
  // Virtual time, for a fresh cell (plc_node's ~reset): the groups read cell, publish at
  // its first scan as on start, and their counts start again from 0.
  void restart(SoftCell& cell);
  // Every group's layout() in cell.
  std::string layout(SoftCell& cell) const;

 private:
  struct Entry {
    std::unique_ptr<TopicGroup> group;
    VirtualRate rate;
    ros::Timer timer;
    uint64_t published = 0;  // publish() calls in virtual time
  };
  std::vector<Entry> entries_;
};

}  // namespace plc_cell
