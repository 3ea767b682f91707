#pragma once
// What makes plc_node's cell scan: the real-time loop or the virtual clock. plc_node has one
// set of topics and services and owns one driver; the driver decides when the cell scans,
// when an input reaches it, what ROS time a scan of the cell's clock is, and on which thread
// the topics are published. So nothing in the node asks which time it runs in.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <ros/time.h>

namespace plc_cell {

class Cell;
class ScanEngine;

// An input from a topic: an X level, an extension's input (a temperature channel's reading), or an X handed back
// to the cell's simulation (~simulate). Stamped: virtual time applies it at its scan.
struct TimedInput {
  uint64_t stamp_us = 0;
  uint64_t seq = 0;  // arrival order breaks ties between equal stamps
  uint32_t x = 0;
  bool v = false;
  std::function<void(ScanEngine&)> change;  // set: an extension's topic input, not an X
  bool resume = false;  // ~simulate: x goes back to the cell's simulation
};

class ScanDriver {
 public:
  // The node, as the driver sees it.
  class Host {
   public:
    virtual ~Host() = default;
    virtual Cell& cell() = 0;
    virtual void apply(ScanEngine& e, const TimedInput& in) = 0;  // PLC lock held
    // After each scan, on the driver's thread, PLC lock not held: the node reads what
    // changed and hands its publishing to post(). Returns the cell's time of that scan.
    virtual uint64_t scanned() = 0;
    // Every topic the node publishes on, with how many messages since the cell was built.
    virtual void count_published(std::vector<std::string>* topics, std::vector<uint64_t>* counts) = 0;
  };
  virtual ~ScanDriver() = default;
  // The cell is built (and in RUN if asked): scans begin.
  virtual void start() = 0;
  // No scan after it returns (before the cell stops).
  virtual void stop() {}
  virtual void input(TimedInput in) = 0;
  // The ROS time of the cell's time cell_us: the stamp of everything read at that scan.
  virtual ros::Time stamp(uint64_t cell_us) const = 0;
  // Runs fn, now or on the node's callback queue, so that a scan never waits for a subscriber.
  virtual void post(std::function<void()> fn) = 0;
  // ~io is published at ~io_rate besides on change (real time: a monitor sees the cell is alive).
  virtual bool republishes() const = 0;
  // Why ~reset is refused here ("" if it is not).
  virtual std::string reset_refusal() const = 0;
  // ~reset: swap puts the fresh cell in place with no scan running; the driver then starts
  // a fresh run of it (its first scan at the next clock message).
  virtual void reset(const std::function<void()>& swap) = 0;
};

}  // namespace plc_cell
