#pragma once
// plc_node's cell on the real-time loop (the Cell's RealTimeLoop): a scan every period of
// the steady clock, inputs applied as they come, topics published from the node's callback
// queue (the scan thread only reads what changed), and ~clock: the ROS time of the cell's
// time 0, then of its scans at ~clock_rate, so that a recording replays in virtual time.
// With ~shared_scan the cell is scanned by the process's one SharedScanThread instead, at
// its own period: many cells in one process (nodelets) then wake once per period.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>

#include <ros/ros.h>

#include "plc_cell/ros/scan_driver.h"
#include "plc_cell/ros/topic_group.h"

namespace plc_cell {

class SharedScanThread;

class RealTimeDriver : public ScanDriver {
 public:
  // Reads ~clock_rate and ~shared_scan; throws Error on a bad rate.
  RealTimeDriver(ros::NodeHandle& nh, ros::NodeHandle& pnh, Host& host);
  ~RealTimeDriver() override;  // drops the callbacks it posted that have not run

  void start() override;
  void stop() override;
  void input(TimedInput in) override;
  ros::Time stamp(uint64_t cell_us) const override;
  void post(std::function<void()> fn) override;
  bool republishes() const override { return true; }
  std::string reset_refusal() const override;
  void reset(const std::function<void()>& swap) override { swap(); }

 protected:
  void after_scan();  // the scan thread

 private:
  void publish_clock(uint64_t cell_us);

  Host& host_;
  bool shared_ = false;      // ~shared_scan
  int shared_threads_ = 1;   // ~shared_scan_threads: the process's shared threads to spread over
  SharedScanThread* shared_thread_ = nullptr;  // the one scanning this cell
  uint64_t shared_id_ = 0;   // its handle in the SharedScanThread, 0: none
  ros::CallbackQueueInterface* queue_;
  ros::Publisher clock_pub_;
  std::unique_ptr<VirtualRate> clock_rate_;  // null: no ~clock
  // The ROS time (ns) of the cell's time 0, set at its first scan; -1 before.
  mutable std::atomic<int64_t> origin_ns_{-1};
  std::mutex clock_mu_;      // one ~clock message at a time, in order
  bool clock_sent_ = false;  // the time 0 went out
};

}  // namespace plc_cell
