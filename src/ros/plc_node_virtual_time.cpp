// plc_node in virtual time (~virtual_time: true): no real-time loop. Each message on
// ~clock_topic (rosgraph_msgs/Clock, default /clock, e.g. `rosbag play --clock`) runs
// every scan at times k * scan_period up to clock - ~virtual_time_lag (the cell's own time
// starting at 0 at the first clock message, or after ~reset at its first scan). Stamped inputs are
// applied before the first scan at or after their stamp, and every change is published
// with its scan's time; the topic groups (counters, axes, temperatures, register groups)
// are published at their rates of virtual time, stamped with their scan. So the same
// inputs and clock give the same outputs on every topic, bit for bit.
// The lag lets inputs that travel on other connections than the clock arrive first; an
// input that still comes after its scan is applied at the next one and counted as late
// (on /diagnostics), since from then on a replay may differ.
//
// ~virtual_time/scanned (ScanProgress) says how far the node got and how many messages it
// published on each topic, so a test driver knows when every message of a scan has
// arrived; ~reset rebuilds the cell from its files for the next test case.
#include <algorithm>
#include <sstream>

#include <rosgraph_msgs/Clock.h>

#include "plc_cell/ScanProgress.h"
#include "plc_cell/core/error.h"
#include "plc_cell/ros/extension_diagnostics.h"
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
  pnh.param("publish_every_scan", every_scan_, every_scan_);
  published_.assign(2 + 2 * signal_pubs_.size(), 0);
  scanned_pub_ = pnh.advertise<ScanProgress>("virtual_time/scanned", 100);
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
      cell_->soft().simulation().override_input(x);
      e.set_input(x, v);
      return 0;
    });
    return;
  }
  std::lock_guard<std::mutex> lk(virtual_mu_);
  if (next_scan_us_ > period_us_ && stamp_us <= next_scan_us_ - period_us_) ++late_inputs_;  // its scan has run
  pending_.push_back({stamp_us, input_seq_++, x, v});
  ++inputs_received_;
  publish_progress();  // a driver knows the input is in before it sends the clock
}

void PlcNode::apply_at(uint64_t stamp_us, std::function<void(ScanEngine&)> change) {
  PendingInput in{stamp_us, 0, 0, false};
  in.change = std::move(change);
  if (!virtual_time_) {
    cell_->plc().locked([&](ScanEngine& e, Memory&) {
      apply(e, in);
      return 0;
    });
    return;
  }
  std::lock_guard<std::mutex> lk(virtual_mu_);
  if (next_scan_us_ > period_us_ && stamp_us <= next_scan_us_ - period_us_) ++late_inputs_;  // its scan has run
  in.seq = input_seq_++;
  pending_.push_back(in);
  ++inputs_received_;
  publish_progress();
}

void PlcNode::apply(ScanEngine& e, const PendingInput& in) {
  if (in.resume) {
    cell_->soft().simulation().resume(in.x);
    return;
  }
  if (in.change) {
    in.change(e);
    return;
  }
  cell_->soft().simulation().override_input(in.x);  // the topic now plays this sensor
  e.set_input(in.x, in.v);
}

void PlcNode::on_clock(uint64_t now_us) {
  std::lock_guard<std::mutex> lk(virtual_mu_);  // one clock message at a time, in order
  if (!clock_started_) {
    // The cell's time 0 (what its simulation, timers and counters see): on start the
    // first clock message's instant, rounded up to a scan, so that a recording's clock
    // (a real-time cell's ~clock starts at its first scan) starts the replayed cell with
    // the recorded one; after ~reset the first scan that message runs (a test driver's
    // first scan). The scans run once the clock is the lag beyond them.
    uint64_t first = now_us;
    if (after_reset_) {
      if (now_us < lag_us_) return;
      first = now_us - lag_us_;
    }
    next_scan_us_ = epoch_us_ = (first + period_us_ - 1) / period_us_ * period_us_;  // first multiple
    clock_started_ = true;
    after_reset_ = false;
  }
  if (now_us < lag_us_ + next_scan_us_) {
    publish_progress();
    return;
  }
  const uint64_t until = now_us - lag_us_;
  std::stable_sort(pending_.begin(), pending_.end(), [](const PendingInput& a, const PendingInput& b) {
    return a.stamp_us != b.stamp_us ? a.stamp_us < b.stamp_us : a.seq < b.seq;
  });
  while (next_scan_us_ <= until) {
    const uint64_t t = next_scan_us_;
    size_t k = 0;
    cell_->plc().locked([&](ScanEngine& e, Memory&) {
      for (; k < pending_.size() && pending_[k].stamp_us <= t; ++k) apply(e, pending_[k]);
      return 0;
    });
    pending_.erase(pending_.begin(), pending_.begin() + long(k));
    cell_->plc().scan(t - epoch_us_);
    Snapshot s = take_snapshot();
    s.scan_us = t;
    if (!virtual_published_ || !(s == virtual_last_)) {
      publish(s, !virtual_published_);
      virtual_published_ = true;
      virtual_last_ = s;
      std::lock_guard<std::mutex> slk(snap_mu_);
      last_published_ = s;
    }
    topic_groups_.after_virtual_scan(t, every_scan_);
    ++scans_;
    last_scan_us_ = t;
    next_scan_us_ += period_us_;
  }
  publish_progress();  // after every message of these scans
}

void PlcNode::publish_progress() {
  ScanProgress m;
  m.header.stamp.fromNSec(last_scan_us_ * 1000);
  m.header.frame_id = frame_id_;
  m.resets = resets_;
  m.scans = scans_;
  m.inputs = inputs_received_;
  m.scan_period.fromNSec(int64_t(period_us_) * 1000);
  m.lag.fromNSec(int64_t(lag_us_) * 1000);
  m.fault = cell_->plc().locked([](ScanEngine& e, Memory&) { return e.fault(); });
  m.topics.push_back(io_pub_.getTopic());
  m.topics.push_back(forced_pub_.getTopic());
  for (const auto& p : signal_pubs_) m.topics.push_back(p.getTopic());
  for (const auto& p : stamped_pubs_) m.topics.push_back(p.getTopic());
  m.published.assign(published_.begin(), published_.end());
  m.topics.push_back(io_words_pub_.getTopic());  // published with every ~io
  m.published.push_back(published_[0]);
  topic_groups_.count_published(&m.topics, &m.published);
  scanned_pub_.publish(m);
}

namespace {

// What a cell's topics are made from: its signals, register groups and what each topic
// group of its extensions publishes. ~reset keeps the node's topics, so the fresh cell must
// give the same.
std::string topic_layout(Cell& cell, const TopicGroups& groups) {
  std::ostringstream out;
  const CellConfig& cfg = cell.config();
  for (const auto& s : cfg.signals) out << "signal " << s.first << '=' << format_address(s.second) << '\n';
  for (const auto& g : cfg.registers) out << "registers " << g.name << ' ' << g.text << ' ' << g.rate_hz << '\n';
  return out.str() + groups.layout(cell.soft());
}

}  // namespace

// A fresh cell for the next test case: built from the same files and parameters, memory as
// on start, its first scan at the next clock message, every topic published again at that
// scan as on start. The ROS side stays: publishers, subscribers and services keep their
// connections, so a driver's subscriptions see the fresh cell at once. plc_node spins one
// thread in virtual time, so no other callback runs meanwhile.
bool PlcNode::on_reset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  res.success = false;
  if (!virtual_time_) {
    res.message = "~reset works in virtual time only (~virtual_time: true); restart plc_node for a fresh cell";
    return true;
  }
  if (cell_->persister()) {
    res.message = "~reset: the cell keeps its retentive memory in " + cell_->persister()->status().file +
                  ", so a fresh cell would not start fresh; run the tests without a persist file";
    return true;
  }
  std::unique_ptr<Cell> fresh;
  try {
    fresh = std::make_unique<Cell>(cell_path_, overrides_, Cell::Purpose::Serve,
                                   [](const std::string& l) { ROS_INFO("plc_node: %s", l.c_str()); });
  } catch (const std::exception& e) {
    res.message = std::string("~reset: ") + e.what() + " (the running cell is kept)";
    return true;
  }
  if (topic_layout(*fresh, topic_groups_) != topic_layout(*cell_, topic_groups_)) {
    res.message = "~reset: the cell's files now give other topics (signals, register groups, counters, axes or "
                  "temperature channels); restart plc_node (the running cell is kept)";
    return true;
  }
  if (autostart_ && !fresh->plc().set_mode(RunMode::Run)) {
    res.message = "~reset: cannot RUN: no program (the running cell is kept)";
    return true;
  }
  std::lock_guard<std::mutex> lk(virtual_mu_);
  for (const auto& name : extension_diagnostics_) updater_.removeByName(name);
  cell_->stop();
  cell_ = std::move(fresh);  // the old cell goes here; nothing holds it any more
  topic_groups_.restart(cell_->soft());
  extension_diagnostics_ = add_extension_diagnostics(updater_, cell_->soft());
  {
    std::lock_guard<std::mutex> plk(path_mu_);
    program_path_ = cell_->program_path();
  }
  std::string served;
  try {
    cell_->start_servers([&](const Server& s) { served += " " + s.describe(); });
  } catch (const std::exception& e) {
    res.message = std::string("~reset: ") + e.what();
    return true;
  }
  pending_.clear();
  next_scan_us_ = last_scan_us_ = 0;
  late_inputs_ = input_seq_ = inputs_received_ = scans_ = 0;
  virtual_published_ = false;  // the first scan publishes every topic, as on start
  clock_started_ = false;
  after_reset_ = true;
  std::fill(published_.begin(), published_.end(), 0);
  ++resets_;
  {
    std::lock_guard<std::mutex> flk(forced_mu_);
    forced_.clear();
  }
  {
    std::lock_guard<std::mutex> slk(snap_mu_);
    last_published_ = Snapshot();
  }
  publish_progress();
  res.success = true;
  res.message = "a fresh cell from " + cell_path_ + "; its first scan at the next clock message";
  return true;
}

}  // namespace plc_cell
