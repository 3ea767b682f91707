// plc_node's connection for the scenario target (scenario_ros_target.h): its clock,
// ~reset, ~read and the count of every topic's messages per scan (see
// scenario_runner_target.cpp for how a scan is known to be complete).
#include <algorithm>
#include <sstream>

#include <rosgraph_msgs/Clock.h>
#include <std_srvs/Trigger.h>

#include "plc_cell/ReadMemory.h"
#include "plc_cell/core/error.h"
#include "plc_cell/ros/scenario_ros_target.h"
#include "plc_cell/scenario/runner.h"

namespace plc_cell {
namespace scenario {

namespace {

bool starts_with(const std::string& s, const std::string& p) { return s.compare(0, p.size(), p) == 0; }
uint64_t round_up(uint64_t v, uint64_t m) { return (v + m - 1) / m * m; }

std::string seconds(double s) {
  std::ostringstream o;
  o << s << " s";
  return o.str();
}

}  // namespace

NodeLink::NodeLink(const std::string& node, const CellConfig& config, uint64_t period_us, uint64_t lag_us,
                   double timeout_s, bool read_fallback)
    : node_(node), config_(config), period_us_(period_us), step_us_(period_us), lag_us_(lag_us), timeout_s_(timeout_s),
      read_fallback_(read_fallback), probes_(registered_topic_probes()), latest_(std::make_unique<Latest>()) {
  nh_.setCallbackQueue(&queue_);
  spinner_ = std::make_unique<ros::AsyncSpinner>(1, &queue_);
  spinner_->start();
}

NodeLink::~NodeLink() {
  spinner_->stop();
  subs_.clear();
  progress_sub_.shutdown();
}

template <class Pred>
bool NodeLink::wait(Pred pred, double timeout_s) {
  std::unique_lock<std::mutex> lk(mu_);
  return cv_.wait_for(lk, std::chrono::duration<double>(timeout_s), pred);
}

// A publisher is used once plc_node has subscribed: a message sent before is lost.
void NodeLink::connect_publisher(ros::Publisher* pub, const std::string& what) {
  if (!wait([&] { return pub->getNumSubscribers() > 0; }, timeout_s_))
    throw Error("plc_node " + node_ + " did not subscribe to " + pub->getTopic() + " within " + seconds(timeout_s_) +
                " (" + what + "): is it running in virtual time (~virtual_time: true)?");
}

// Keeps the latest message of topic stamped at or after the case's time 0 (one of an
// earlier case may still be on its way) with store(latest, msg), and counts it.
template <class M, class Store>
ros::Subscriber NodeLink::keep(const std::string& topic, Store store) {
  return nh_.subscribe<M>(topic, 1000, [this, topic, store](const typename M::ConstPtr& m) {
    std::lock_guard<std::mutex> lk(mu_);
    if (m->header.stamp.toNSec() < t0_us_ * 1000) return;
    ++received_[topic];
    store(*latest_, *m);
    cv_.notify_all();
  });
}

// A publisher whose subscribers' arrival wakes connect_publisher().
template <class M>
ros::Publisher NodeLink::advertise(const std::string& topic) {
  return advertise(ros::AdvertiseOptions::create<M>(topic, 1000, ros::SubscriberStatusCallback(),
                                                    ros::SubscriberStatusCallback(), ros::VoidConstPtr(), nullptr));
}

ros::Publisher NodeLink::advertise(ros::AdvertiseOptions ao) {
  ao.connect_cb = [this](const ros::SingleSubscriberPublisher&) { cv_.notify_all(); };
  ao.callback_queue = &queue_;
  return nh_.advertise(ao);
}

void NodeLink::received(const std::string& topic, uint64_t stamp_ns, const std::function<void()>& store) {
  std::lock_guard<std::mutex> lk(mu_);
  if (stamp_ns < t0_us_ * 1000) return;
  ++received_[topic];
  store();
  cv_.notify_all();
}

ros::Time NodeLink::next_input_stamp() {
  std::lock_guard<std::mutex> lk(mu_);
  const uint64_t next = scanned_ ? last_t_us_ + step_us_ : 0;
  ++inputs_sent_;
  ros::Time t;
  t.fromNSec((t0_us_ + next) * 1000);
  return t;
}

void NodeLink::clear_case() {
  received_.clear();
  *latest_ = Latest();
  for (auto& p : probes_) p->clear();
  have_progress_ = false;
}

TopicProbes* NodeLink::probes_of(const Probe& p) const {
  for (const auto& side : probes_) {
    const auto fs = side->families();
    if (std::find(fs.begin(), fs.end(), p.family) != fs.end()) return side.get();
  }
  return nullptr;
}

void NodeLink::subscribe(const std::string& topic) {
  const std::string rel = topic.substr(node_.size() + 1);
  ros::Subscriber s;
  if (rel == "io") {
    s = keep<IoState>(topic, [](Latest& l, const IoState& m) {
      l.io = m;
      l.have_io = true;
    });
  } else if (starts_with(rel, "signals_stamped/")) {
    s = keep<Signal>(topic, [topic](Latest& l, const Signal& m) { l.signals[topic] = m.data; });
  } else if (starts_with(rel, "registers/")) {
    s = keep<RegisterBlock>(topic, [topic](Latest& l, const RegisterBlock& m) { l.registers[topic] = m; });
  } else {
    bool read = false;
    for (auto& side : probes_)
      if ((read = side->subscribe(*this, topic, &s))) break;
    if (!read) return;  // not read by any probe: ~forced, ~signals/<name> (no stamp), ~counters, joint_states
  }
  subs_.push_back(s);
  topics_.push_back(topic);
}

void NodeLink::call_reset() {
  std_srvs::Trigger srv;
  if (!ros::service::call(node_ + "/reset", srv))
    throw Error("plc_node " + node_ + ": ~reset could not be called (is the node running?)");
  if (!srv.response.success) throw Error("plc_node " + node_ + ": " + srv.response.message);
}

void NodeLink::publish_clock(uint64_t t_us) {
  rosgraph_msgs::Clock c;
  c.clock.fromNSec((t0_us_ + t_us + lag_us_) * 1000);
  clock_pub_.publish(c);
}

bool NodeLink::scan_complete(uint64_t t_us) const {
  if (!have_progress_ || progress_.header.stamp.toNSec() < (t0_us_ + t_us) * 1000 || progress_.scans == 0) return false;
  for (size_t i = 0; i < progress_.topics.size() && i < progress_.published.size(); ++i) {
    const auto r = received_.find(progress_.topics[i]);
    if (std::find(topics_.begin(), topics_.end(), progress_.topics[i]) == topics_.end()) continue;
    if ((r == received_.end() ? 0 : r->second) < progress_.published[i]) return false;
  }
  return true;
}

void NodeLink::advertise_inputs() {
  for (const auto& s : config_.signals)
    if (s.second.area == Area::X) input_pubs_[s.second.index] = advertise<Signal>(node_ + "/inputs_stamped/" + s.first);
  progress_sub_ = nh_.subscribe<ScanProgress>(node_ + "/virtual_time/scanned", 1000,
                                              [this](const ScanProgress::ConstPtr& m) {
                                                std::lock_guard<std::mutex> lk(mu_);
                                                if (resets_known_ && m->resets != resets_) return;  // another case's
                                                progress_ = *m;
                                                have_progress_ = true;
                                                cv_.notify_all();
                                              });
}

void NodeLink::start_case(uint64_t t0_us, bool counted) {
  std::lock_guard<std::mutex> lk(mu_);
  t0_us_ = t0_us;
  next_t0_us_ = std::max(next_t0_us_, t0_us_ + 1000000);
  clear_case();
  inputs_sent_ = 0;
  scanned_ = false;
  last_t_us_ = 0;
  if (counted) ++resets_;  // the progress of this reset on
  read_cache_.clear();
}

uint64_t NodeLink::next_t0() const {
  std::lock_guard<std::mutex> lk(mu_);
  return next_t0_us_;
}

// The topic list comes with the message a reset publishes: true once it is subscribed (a
// round of reset and first scan is then needed to see every topic connected).
bool NodeLink::take_topics(double timeout_s) {
  if (!topics_.empty()) return false;
  if (!wait([&] { return have_progress_; }, timeout_s)) return true;
  std::vector<std::string> topics;
  {
    std::lock_guard<std::mutex> lk(mu_);
    topics = progress_.topics;
    if (progress_.scan_period.toNSec() != int64_t(period_us_) * 1000 || progress_.lag.toNSec() != int64_t(lag_us_) * 1000)
      throw Error("plc_node " + node_ + " scans every " + std::to_string(progress_.scan_period.toNSec() / 1000) +
                  " us with a lag of " + std::to_string(progress_.lag.toNSec() / 1000) + " us; expected " +
                  std::to_string(period_us_) + " and " + std::to_string(lag_us_));
  }
  for (const auto& t : topics)
    if (starts_with(t, node_ + "/")) subscribe(t);
  for (auto& side : probes_) side->connect(*this);
  return true;
}

bool NodeLink::await_first_scan(double timeout_s) {
  return wait([&] { return scan_complete(0); }, timeout_s);
}

void NodeLink::mark_connected() {
  std::lock_guard<std::mutex> lk(mu_);
  resets_ = progress_.resets;
  resets_known_ = true;
  connected_ = true;
}

std::string NodeLink::missing() {
  std::lock_guard<std::mutex> lk(mu_);
  std::string out;
  if (!have_progress_) out = node_ + ": no ~virtual_time/scanned message";
  for (size_t i = 0; i < progress_.topics.size() && i < progress_.published.size(); ++i) {
    const uint64_t got = received_[progress_.topics[i]];
    if (std::find(topics_.begin(), topics_.end(), progress_.topics[i]) != topics_.end() && got < progress_.published[i])
      out += (out.empty() ? "" : ", ") + progress_.topics[i] + " " + std::to_string(got) + " of " +
             std::to_string(progress_.published[i]);
  }
  return out;
}

void NodeLink::connect() {
  if (connected_) return;
  std::string clock_topic = "/clock";
  ros::param::get(node_ + "/clock_topic", clock_topic);
  if (clock_topic.empty() || clock_topic[0] != '/') clock_topic = node_ + "/" + clock_topic;  // plc_node's private name
  clock_pub_ = advertise<rosgraph_msgs::Clock>(clock_topic);
  advertise_inputs();
  if (!ros::service::waitForService(node_ + "/reset", ros::Duration(timeout_s_)))
    throw Error("plc_node " + node_ + " has no ~reset service within " + seconds(timeout_s_) + ": is it running?");
  connect_publisher(&clock_pub_, "its ~clock_topic");
  for (auto& p : input_pubs_) connect_publisher(&p.second, "a named input");
  // Subscriptions connect in the background: a message published before one is up is lost
  // to it. So: reset, scan once and see every topic's messages arrive; else again.
  const double attempt_s = std::min(timeout_s_, 3.0);
  std::string why = "no ~virtual_time/scanned message";
  for (int attempt = 0; attempt < 10; ++attempt) {
    start_case(round_up(next_t0(), period_us_), false);
    call_reset();
    if (take_topics(attempt_s)) continue;
    publish_clock(0);
    if (await_first_scan(attempt_s)) return mark_connected();
    why = missing();
  }
  throw Error("plc_node " + node_ + ": a scan's messages did not all arrive (" + why + ")");
}

void NodeLink::begin_case() {
  connect();
  start_case(round_up(next_t0(), period_us_), true);
  call_reset();
}

// An address on no topic, with ~read: exact in virtual time, where plc_node serves it
// between two clock messages. Once per scan and address.
uint32_t NodeLink::read_memory(const std::string& name) {
  const auto cached = read_cache_.find(name);
  if (cached != read_cache_.end()) return cached->second;
  if (!read_client_.isValid()) read_client_ = ros::NodeHandle().serviceClient<ReadMemory>(node_ + "/read", true);
  ReadMemory srv;
  srv.request.address = name;
  srv.request.count = 1;
  if (!read_client_.call(srv)) {
    read_client_ = ros::NodeHandle().serviceClient<ReadMemory>(node_ + "/read", true);
    if (!read_client_.call(srv)) throw Error("plc_node " + node_ + ": ~read " + name + " failed");
  }
  if (!srv.response.success || srv.response.values.empty()) throw Error("~read " + name + ": " + srv.response.message);
  return read_cache_[name] = uint32_t(srv.response.values[0]);
}

void NodeLink::await_inputs() {
  uint64_t sent;
  read_cache_.clear();
  {
    std::lock_guard<std::mutex> lk(mu_);
    sent = inputs_sent_;
  }
  if (sent && !wait([&] { return have_progress_ && progress_.inputs >= sent; }, timeout_s_))
    throw Error("plc_node " + node_ + " did not acknowledge " + std::to_string(sent) + " stamped inputs within " +
                seconds(timeout_s_));
}

// The node's scan at t_us (its own, at or before the runner's step) and every message of it.
void NodeLink::await_scan(uint64_t t_us) {
  if (!wait([&] { return scan_complete(t_us); }, timeout_s_)) {
    std::lock_guard<std::mutex> lk(mu_);
    std::string why = have_progress_ ? "it reported the scan at " +
                                           format_time(progress_.header.stamp.toNSec() / 1000 - std::min<uint64_t>(
                                               t0_us_, progress_.header.stamp.toNSec() / 1000))
                                     : "no ~virtual_time/scanned message";
    throw Error("plc_node " + node_ + ": the scan at " + format_time(t_us) + " did not complete within " +
                seconds(timeout_s_) + " (" + why + ")");
  }
}

void NodeLink::stepped(uint64_t t_us) {
  std::lock_guard<std::mutex> lk(mu_);
  scanned_ = true;
  last_t_us_ = t_us;
  next_t0_us_ = std::max(next_t0_us_, t0_us_ + t_us + 1000000);
}

void NodeLink::scan(uint64_t t_us) {
  await_inputs();
  publish_clock(t_us);
  await_scan(t_us);
  stepped(t_us);
}

}  // namespace scenario
}  // namespace plc_cell
