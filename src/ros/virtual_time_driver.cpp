#include "plc_cell/ros/virtual_time_driver.h"

#include <algorithm>

#include <rosgraph_msgs/Clock.h>

#include "plc_cell/ScanProgress.h"
#include "plc_cell/core/error.h"
#include "plc_cell/runtime/cell.h"

namespace plc_cell {

VirtualTimeDriver::VirtualTimeDriver(ros::NodeHandle& pnh, Host& host, diagnostic_updater::Updater& updater,
                                     uint64_t period_us, std::string frame_id)
    : host_(host), frame_id_(std::move(frame_id)), period_us_(std::max<uint64_t>(period_us, 1)), pnh_(pnh) {
  double lag = 0.1;
  pnh.param<std::string>("clock_topic", clock_topic_, "/clock");
  pnh.param("virtual_time_lag", lag, lag);
  if (!(lag >= 0 && lag <= 60)) throw Error("~virtual_time_lag must be in [0, 60] s");
  lag_us_ = uint64_t(lag * 1e6);
  scanned_pub_ = pnh.advertise<ScanProgress>("virtual_time/scanned", 100);
  updater.add("virtual time", [this](diagnostic_updater::DiagnosticStatusWrapper& stat) {
    std::lock_guard<std::mutex> lk(mu_);
    if (run_->late_inputs) stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "inputs arrived after their scan");
    else stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "deterministic");
    stat.add("next scan (us)", run_->next_scan_us);
    stat.add("late inputs", run_->late_inputs);
    stat.add("pending inputs", run_->pending.size());
  });
}

void VirtualTimeDriver::start() {
  clock_sub_ = pnh_.subscribe<rosgraph_msgs::Clock>(clock_topic_, 1000, [this](const rosgraph_msgs::Clock::ConstPtr& m) {
    on_clock(m->clock.toNSec() / 1000);
  });
}

void VirtualTimeDriver::input(TimedInput in) {
  std::lock_guard<std::mutex> lk(mu_);
  Run& r = *run_;
  if (in.resume) {  // a hand-back: at the next scan, not a stamped input
    in.stamp_us = r.next_scan_us;
    in.seq = r.input_seq++;
    r.pending.push_back(in);
    return;
  }
  if (r.next_scan_us > period_us_ && in.stamp_us <= r.next_scan_us - period_us_) ++r.late_inputs;  // its scan ran
  in.seq = r.input_seq++;
  r.pending.push_back(in);
  ++r.inputs_received;
  publish_progress();  // a driver knows the input is in before it sends the clock
}

// The cell scans at clock time epoch + its own time.
ros::Time VirtualTimeDriver::stamp(uint64_t cell_us) const {
  ros::Time t;
  t.fromNSec((run_->epoch_us + cell_us) * 1000);
  return t;
}

void VirtualTimeDriver::on_clock(uint64_t now_us) {
  std::lock_guard<std::mutex> lk(mu_);  // one clock message at a time, in order
  Run& r = *run_;
  if (!r.started) {
    // The cell's time 0 (what its simulation, timers and counters see): on start the
    // first clock message's instant, rounded up to a scan, so that a recording's clock
    // (a real-time cell's ~clock starts at its first scan) starts the replayed cell with
    // the recorded one; after ~reset the first scan that message runs (a test driver's
    // first scan). The scans run once the clock is the lag beyond them.
    uint64_t first = now_us;
    if (r.after_reset) {
      if (now_us < lag_us_) return;
      first = now_us - lag_us_;
    }
    r.next_scan_us = r.epoch_us = (first + period_us_ - 1) / period_us_ * period_us_;  // first multiple
    r.started = true;
  }
  if (now_us >= lag_us_ + r.next_scan_us) {
    const uint64_t until = now_us - lag_us_;
    std::stable_sort(r.pending.begin(), r.pending.end(), [](const TimedInput& a, const TimedInput& b) {
      return a.stamp_us != b.stamp_us ? a.stamp_us < b.stamp_us : a.seq < b.seq;
    });
    for (; r.next_scan_us <= until; r.next_scan_us += period_us_) scan(r.next_scan_us);
  }
  publish_progress();  // after every message of these scans
}

void VirtualTimeDriver::scan(uint64_t t) {
  Run& r = *run_;
  Cell& cell = host_.cell();
  size_t k = 0;
  cell.plc().locked([&](ScanEngine& e, Memory&) {
    for (; k < r.pending.size() && r.pending[k].stamp_us <= t; ++k) host_.apply(e, r.pending[k]);
    return 0;
  });
  r.pending.erase(r.pending.begin(), r.pending.begin() + long(k));
  cell.plc().scan(t - r.epoch_us);
  host_.scanned();
  ++r.scans;
  r.last_scan_us = t;
}

void VirtualTimeDriver::reset(const std::function<void()>& swap) {
  std::lock_guard<std::mutex> lk(mu_);
  swap();
  run_ = std::make_unique<Run>(true);
  ++resets_;
  publish_progress();
}

void VirtualTimeDriver::publish_progress() {
  const Run& r = *run_;
  ScanProgress m;
  m.header.stamp.fromNSec(r.last_scan_us * 1000);
  m.header.frame_id = frame_id_;
  m.resets = resets_;
  m.scans = r.scans;
  m.inputs = r.inputs_received;
  m.scan_period.fromNSec(int64_t(period_us_) * 1000);
  m.lag.fromNSec(int64_t(lag_us_) * 1000);
  m.fault = host_.cell().plc().locked([](ScanEngine& e, Memory&) { return e.fault(); });
  std::vector<uint64_t> counts;
  host_.count_published(&m.topics, &counts);
  m.published.assign(counts.begin(), counts.end());
  scanned_pub_.publish(m);
}

}  // namespace plc_cell
