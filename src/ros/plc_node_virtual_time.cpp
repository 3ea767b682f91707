// plc_node in virtual time (~virtual_time: true): no real-time loop. Each message on
// ~clock_topic (rosgraph_msgs/Clock, default /clock, e.g. `rosbag play --clock`) runs
// every scan at times k * scan_period up to clock - ~virtual_time_lag. Stamped inputs are
// applied before the first scan at or after their stamp, and every change is published
// with its scan's time; the topic groups (counters, axes, temperatures, register groups)
// are published at their rates of virtual time, stamped with their scan. So the same
// inputs and clock give the same outputs on every topic, bit for bit.
// The lag lets inputs that travel on other connections than the clock arrive first; an
// input that still comes after its scan is applied at the next one and counted as late
// (on /diagnostics), since from then on a replay may differ.
#include <algorithm>

#include <rosgraph_msgs/Clock.h>

#include "plc_cell/core/error.h"
#include "plc_cell/ros/plc_node.h"

namespace plc_cell {

void PlcNode::start_virtual_time(ros::NodeHandle& pnh, uint64_t period_us) {
  std::string topic = "/clock";
  double lag = 0.1;
  pnh.param<std::string>("clock_topic", topic, topic);
  pnh.param("virtual_time_lag", lag, lag);
  if (!(lag >= 0 && lag <= 60)) throw Error("~virtual_time_lag must be in [0, 60] s");
  period_us_ = std::max<uint64_t>(period_us, 1);
  lag_us_ = uint64_t(lag * 1e6);
  updater_.add("virtual time", [this](diagnostic_updater::DiagnosticStatusWrapper& stat) {
    std::lock_guard<std::mutex> lk(virtual_mu_);
    if (late_inputs_) stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "inputs arrived after their scan");
    else stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "deterministic");
    stat.add("next scan (us)", next_scan_us_);
    stat.add("late inputs", late_inputs_);
    stat.add("pending inputs", pending_.size());
  });
  clock_sub_ = pnh.subscribe<rosgraph_msgs::Clock>(topic, 1000, [this](const rosgraph_msgs::Clock::ConstPtr& m) {
    on_clock(m->clock.toNSec() / 1000);
  });
}

void PlcNode::on_stamped_input(uint32_t x, uint64_t stamp_us, bool v) {
  if (!virtual_time_) {
    cell_->plc().locked([&](ScanEngine& e, Memory&) {
      cell_->soft().simulation().release(x);
      e.set_input(x, v);
      return 0;
    });
    return;
  }
  std::lock_guard<std::mutex> lk(virtual_mu_);
  if (next_scan_us_ > period_us_ && stamp_us <= next_scan_us_ - period_us_) ++late_inputs_;  // its scan has run
  pending_.push_back({stamp_us, input_seq_++, x, v});
}

void PlcNode::on_clock(uint64_t now_us) {
  std::lock_guard<std::mutex> lk(virtual_mu_);  // one clock message at a time, in order
  if (now_us < lag_us_) return;
  const uint64_t until = now_us - lag_us_;
  if (!next_scan_us_) next_scan_us_ = (until + period_us_ - 1) / period_us_ * period_us_;  // first multiple
  std::stable_sort(pending_.begin(), pending_.end(), [](const PendingInput& a, const PendingInput& b) {
    return a.stamp_us != b.stamp_us ? a.stamp_us < b.stamp_us : a.seq < b.seq;
  });
  while (next_scan_us_ <= until) {
    const uint64_t t = next_scan_us_;
    size_t k = 0;
    cell_->plc().locked([&](ScanEngine& e, Memory&) {
      for (; k < pending_.size() && pending_[k].stamp_us <= t; ++k) {
        cell_->soft().simulation().release(pending_[k].x);  // the topic now plays this sensor
        e.set_input(pending_[k].x, pending_[k].v);
      }
      return 0;
    });
    pending_.erase(pending_.begin(), pending_.begin() + long(k));
    cell_->plc().scan(t);
    Snapshot s = take_snapshot();
    s.scan_us = t;
    if (!virtual_published_ || !(s == virtual_last_)) {
      publish(s, !virtual_published_);
      virtual_published_ = true;
      virtual_last_ = s;
      std::lock_guard<std::mutex> slk(snap_mu_);
      last_published_ = s;
    }
    topic_groups_.after_virtual_scan(t);
    next_scan_us_ += period_us_;
  }
}

}  // namespace plc_cell
