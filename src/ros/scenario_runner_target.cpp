// plc_node as a scenario target: scans by clock messages, reads from the topics a robot
// stack subscribes to, drives through ~inputs_stamped/<name>, ~write, ~force, ~release and
// ~simulate.
//
// Synchronisation: plc_node publishes each topic on its own connection, so nothing orders
// them. After the clock message of the scan at t, plc_node publishes on
// ~virtual_time/scanned how many messages it has put on each topic since ~reset; the scan
// is complete here once that message says it scanned t and this node has received as many
// messages, stamped at or after the case's time 0, on every topic it reads. A stamped input
// is acknowledged the same way (ScanProgress.inputs) before the clock that scans it goes out.
#include "plc_cell/ros/scenario_ros_target.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/Temperature.h>
#include <std_srvs/Trigger.h>

#include "plc_cell/ForceDiscrete.h"
#include "plc_cell/ReadMemory.h"
#include "plc_cell/ReleaseDiscrete.h"
#include "plc_cell/SimulateInputs.h"
#include "plc_cell/WriteMemory.h"
#include "plc_cell/core/address.h"
#include "plc_cell/core/area.h"
#include "plc_cell/core/error.h"
#include "plc_cell/scenario/runner.h"

namespace plc_cell {
namespace scenario {

struct NodeLink::Latest {
  IoState io;
  bool have_io = false;
  std::map<std::string, bool> signals;  // by topic
  std::map<std::string, RegisterBlock> registers;
  std::map<std::string, Counter> counters;
  std::map<std::string, PulseMeasurement> pulses;
  std::map<std::string, AxisStatus> axes;
  std::map<std::string, double> temperatures;
};

namespace {

bool starts_with(const std::string& s, const std::string& p) { return s.compare(0, p.size(), p) == 0; }
bool ends_with(const std::string& s, const std::string& p) {
  return s.size() >= p.size() && s.compare(s.size() - p.size(), p.size(), p) == 0;
}

uint64_t round_up(uint64_t v, uint64_t m) { return (v + m - 1) / m * m; }

std::string number_text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

// The position of a in a group's RegisterBlock values.
bool element_of(const RegisterGroup& g, const Address& a, size_t* idx) {
  size_t i = 0;
  for (const auto& sp : g.spans) {
    Address e = sp.start;
    const uint32_t stride = element_stride(e);
    for (uint32_t k = 0; k < sp.count; ++k, e.index += stride, ++i)
      if (e == a) {
        *idx = i;
        return true;
      }
  }
  return false;
}

std::string seconds(double s) {
  std::ostringstream o;
  o << s << " s";
  return o.str();
}

}  // namespace

NodeLink::NodeLink(const std::string& node, const CellConfig& config, uint64_t period_us, uint64_t lag_us,
                   double timeout_s, bool read_fallback)
    : node_(node), config_(config), period_us_(period_us), lag_us_(lag_us), timeout_s_(timeout_s),
      read_fallback_(read_fallback), latest_(std::make_unique<Latest>()) {
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
  ros::AdvertiseOptions ao = ros::AdvertiseOptions::create<M>(
      topic, 1000, [this](const ros::SingleSubscriberPublisher&) { cv_.notify_all(); }, ros::SubscriberStatusCallback(),
      ros::VoidConstPtr(), &queue_);
  return nh_.advertise(ao);
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
  } else if (starts_with(rel, "pulses/")) {
    s = keep<PulseMeasurement>(topic, [topic](Latest& l, const PulseMeasurement& m) { l.pulses[topic] = m; });
  } else if (starts_with(rel, "counters/")) {
    s = keep<Counter>(topic, [topic](Latest& l, const Counter& m) { l.counters[topic] = m; });
  } else if (starts_with(rel, "motion/") && ends_with(rel, "/status")) {
    s = keep<AxisStatus>(topic, [topic](Latest& l, const AxisStatus& m) { l.axes[topic] = m; });
  } else if (starts_with(rel, "temperature/")) {
    const std::string channel = rel.substr(std::string("temperature/").size());
    temperature_pubs_[channel] = advertise<sensor_msgs::Temperature>(node_ + "/temperature_inputs/" + channel);
    s = keep<sensor_msgs::Temperature>(
        topic, [topic](Latest& l, const sensor_msgs::Temperature& m) { l.temperatures[topic] = m.temperature; });
  } else {
    return;  // not read by any probe: ~forced, ~signals/<name> (no stamp), ~counters, joint_states
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

void NodeLink::connect() {
  if (connected_) return;
  std::string clock_topic = "/clock";
  ros::param::get(node_ + "/clock_topic", clock_topic);
  if (clock_topic.empty() || clock_topic[0] != '/') clock_topic = node_ + "/" + clock_topic;  // plc_node's private name
  clock_pub_ = advertise<rosgraph_msgs::Clock>(clock_topic);
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
  if (!ros::service::waitForService(node_ + "/reset", ros::Duration(timeout_s_)))
    throw Error("plc_node " + node_ + " has no ~reset service within " + seconds(timeout_s_) + ": is it running?");
  connect_publisher(&clock_pub_, "its ~clock_topic");
  for (auto& p : input_pubs_) connect_publisher(&p.second, "a named input");
  // Subscriptions connect in the background: a message published before one is up is lost
  // to it. So: reset, scan once and see every topic's messages arrive; else again.
  const double attempt_s = std::min(timeout_s_, 3.0);
  std::string missing = "no ~virtual_time/scanned message";
  for (int attempt = 0; attempt < 10; ++attempt) {
    {
      std::lock_guard<std::mutex> lk(mu_);
      t0_us_ = round_up(next_t0_us_, period_us_);
      next_t0_us_ = t0_us_ + 1000000;
      received_.clear();
      *latest_ = Latest();
      have_progress_ = false;
    }
    call_reset();
    if (topics_.empty()) {  // the topic list comes with the message ~reset publishes
      if (!wait([&] { return have_progress_; }, attempt_s)) continue;
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
      for (auto& p : temperature_pubs_) connect_publisher(&p.second, "a temperature channel's input");
      continue;
    }
    publish_clock(0);
    if (wait([&] { return scan_complete(0); }, attempt_s)) {
      std::lock_guard<std::mutex> lk(mu_);
      resets_ = progress_.resets;
      resets_known_ = true;
      connected_ = true;
      return;
    }
    std::lock_guard<std::mutex> lk(mu_);
    missing.clear();
    if (!have_progress_) missing = "no ~virtual_time/scanned message";
    for (size_t i = 0; i < progress_.topics.size() && i < progress_.published.size(); ++i) {
      const uint64_t got = received_[progress_.topics[i]];
      if (std::find(topics_.begin(), topics_.end(), progress_.topics[i]) != topics_.end() && got < progress_.published[i])
        missing += (missing.empty() ? "" : ", ") + progress_.topics[i] + " " + std::to_string(got) + " of " +
                   std::to_string(progress_.published[i]);
    }
  }
  throw Error("plc_node " + node_ + ": a scan's messages did not all arrive (" + missing + ")");
}

void NodeLink::begin_case() {
  connect();
  {
    std::lock_guard<std::mutex> lk(mu_);
    t0_us_ = round_up(next_t0_us_, period_us_);
    next_t0_us_ = t0_us_ + 1000000;
    received_.clear();
    *latest_ = Latest();
    have_progress_ = false;
    inputs_sent_ = 0;
    scanned_ = false;
    last_t_us_ = 0;
    ++resets_;  // the progress of this reset on
  }
  read_cache_.clear();
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

void NodeLink::scan(uint64_t t_us) {
  uint64_t sent;
  read_cache_.clear();
  {
    std::lock_guard<std::mutex> lk(mu_);
    sent = inputs_sent_;
  }
  if (sent && !wait([&] { return have_progress_ && progress_.inputs >= sent; }, timeout_s_))
    throw Error("plc_node " + node_ + " did not acknowledge " + std::to_string(sent) + " stamped inputs within " +
                seconds(timeout_s_));
  publish_clock(t_us);
  if (!wait([&] { return scan_complete(t_us); }, timeout_s_)) {
    std::lock_guard<std::mutex> lk(mu_);
    std::string why = have_progress_ ? "it reported the scan at " +
                                           format_time(progress_.header.stamp.toNSec() / 1000 - std::min<uint64_t>(
                                               t0_us_, progress_.header.stamp.toNSec() / 1000))
                                     : "no ~virtual_time/scanned message";
    throw Error("plc_node " + node_ + ": the scan at " + format_time(t_us) + " did not complete within " +
                seconds(timeout_s_) + " (" + why + ")");
  }
  std::lock_guard<std::mutex> lk(mu_);
  scanned_ = true;
  last_t_us_ = t_us;
  next_t0_us_ = std::max(next_t0_us_, t0_us_ + t_us + 1000000);
}

// ---- RosTarget ----

RosTarget::RosTarget(NodeLink& link) : link_(link) { link_.begin_case(); }

bool RosTarget::has_topic(const std::string& private_name) const {
  const std::string t = link_.node_ + "/" + private_name;
  return std::find(link_.topics_.begin(), link_.topics_.end(), t) != link_.topics_.end();
}

std::string RosTarget::topic_of(const Address& a) const {
  if ((a.area == Area::X || a.area == Area::Y) && a.width == Width::Bit && a.index < 256) return link_.node_ + "/io";
  for (const auto& s : link_.config_.signals)
    if (s.second == a && has_topic("signals_stamped/" + s.first)) return link_.node_ + "/signals_stamped/" + s.first;
  size_t idx;
  for (const auto& g : link_.config_.registers)
    if (element_of(g, a, &idx) && has_topic("registers/" + g.name)) return link_.node_ + "/registers/" + g.name;
  return "";
}

std::string RosTarget::check(const Probe& p, bool writing) {
  switch (p.kind) {
    case Probe::Kind::Address: {
      Address a;
      try {
        a = link_.config_.resolve(p.name);
      } catch (const std::exception& e) {
        return e.what();
      }
      try {
        check_format(a, p.format, p.text);
      } catch (const std::exception& e) {
        return e.what();
      }
      if (writing) return "";  // ~write, ~force take any address; set() on an X needs its name
      if (topic_of(a).empty() && !link_.read_fallback_)
        return p.name + " is on no topic of plc_node: add it to a group of the cell YAML's registers: (or, for a bit, "
                        "name it in signals:)";
      return "";
    }
    case Probe::Kind::Counter:
      if (writing) return p.text + ": plc_node has no topic or service that sets a counter in a scenario";
      if (!has_topic("counters/" + p.name))
        return p.text + ": plc_node publishes no ~counters/" + p.name + " (no counter of that name in the cell)";
      return "";
    case Probe::Kind::AxisPosition:
    case Probe::Kind::AxisState:
    case Probe::Kind::AxisFrequency:
      if (writing) return p.text + ": an axis cannot be driven by a scenario step";
      if (!has_topic("motion/" + p.name + "/status"))
        return p.text + ": plc_node publishes no ~motion/" + p.name + "/status (no axis of that name in the cell)";
      return "";
    case Probe::Kind::Temperature:
      if (!has_topic("temperature/" + p.name))
        return p.text + ": plc_node publishes no ~temperature/" + p.name + " (no channel of that name in the cell)";
      return "";
    case Probe::Kind::PulseWidth:
    case Probe::Kind::PulsePeriod:
    case Probe::Kind::PulseFrequency:
      if (writing) return p.text + ": a pulse measurement is read, not driven";
      if (!has_topic("pulses/" + p.name))
        return p.text + ": plc_node publishes no ~pulses/" + p.name + " (the input is not measured in the cell)";
      return "";
    case Probe::Kind::Analog:
      return p.text + ": plc_node has no topic for analog input channels" +
             std::string(writing ? " and no way to set one" : "") + "; run this case with `plc_cell test`";
  }
  return p.text + ": unknown probe";
}

Reading RosTarget::read(const Probe& p) {
  if (p.kind == Probe::Kind::Address) {
    const Address a = link_.config_.resolve(p.name);
    if (topic_of(a).empty()) return address_reading(a, link_.read_memory(p.name), p.format);
  }
  std::lock_guard<std::mutex> lk(link_.mu_);
  const NodeLink::Latest& l = *link_.latest_;
  Reading r;
  switch (p.kind) {
    case Probe::Kind::Address: {
      const Address a = link_.config_.resolve(p.name);
      const std::string topic = topic_of(a);
      uint32_t raw = 0;
      if (topic == link_.node_ + "/io") {
        if (l.have_io) {
          const auto& v = a.area == Area::X ? l.io.x : l.io.y;
          raw = a.index < v.size() && v[a.index];
        }
      } else if (l.signals.count(topic)) {
        raw = l.signals.at(topic);
      } else if (l.registers.count(topic)) {
        const std::string group = topic.substr(topic.rfind('/') + 1);
        size_t idx = 0;
        for (const auto& g : link_.config_.registers)
          if (g.name == group && element_of(g, a, &idx)) break;
        const auto& vals = l.registers.at(topic).values;
        if (idx < vals.size()) raw = uint32_t(vals[idx]);
      }
      return address_reading(a, raw, p.format);
    }
    case Probe::Kind::Counter: {
      const auto it = l.counters.find(link_.node_ + "/counters/" + p.name);
      r.number = it == l.counters.end() ? 0 : double(it->second.count);
      r.text = number_text(r.number);
      return r;
    }
    case Probe::Kind::AxisPosition:
    case Probe::Kind::AxisState:
    case Probe::Kind::AxisFrequency: {
      const auto it = l.axes.find(link_.node_ + "/motion/" + p.name + "/status");
      AxisStatus s;
      if (it != l.axes.end()) s = it->second;
      // As the cell in process reads it: pulses, Hz signed by the direction, and the state
      // an error code, else pulses going out, else idle.
      if (p.kind == Probe::Kind::AxisState) {
        r.word = s.error ? "error" : s.frequency != 0 ? "moving" : "idle";
        r.number = s.error;
        r.text = s.error ? "error " + std::to_string(s.error) : r.word;
        return r;
      }
      r.number = p.kind == Probe::Kind::AxisPosition ? double(s.pulses) : s.frequency;
      r.text = number_text(r.number);
      return r;
    }
    case Probe::Kind::Temperature: {
      const auto it = l.temperatures.find(link_.node_ + "/temperature/" + p.name);
      const double c = it == l.temperatures.end() ? std::nan("") : it->second;
      r.valid = std::isfinite(c);  // NaN: a broken line
      r.number = r.valid ? c : 0;
      r.text = r.valid ? number_text(std::round(c * 1000) / 1000) + " C" : "NaN (broken)";
      return r;
    }
    case Probe::Kind::PulseWidth:
    case Probe::Kind::PulsePeriod:
    case Probe::Kind::PulseFrequency: {
      const auto it = l.pulses.find(link_.node_ + "/pulses/" + p.name);
      PulseMeasurement m;
      if (it != l.pulses.end()) m = it->second;
      r.number = p.kind == Probe::Kind::PulseWidth ? m.width : p.kind == Probe::Kind::PulsePeriod ? m.period : m.frequency;
      r.text = number_text(r.number);
      return r;
    }
    case Probe::Kind::Analog:
      break;
  }
  r.valid = false;
  r.text = "unreadable";
  return r;
}

void RosTarget::set(const Probe& p, const Value& v) {
  if (p.kind == Probe::Kind::Temperature) {
    const auto it = link_.temperature_pubs_.find(p.name);
    if (it == link_.temperature_pubs_.end()) throw Error(check(p, true));
    if (v.has_unit && v.quantity.unit != temp::Unit::Celsius)
      throw Error(p.text + ": " + v.text + ": plc_node's ~temperature_inputs/" + p.name +
                  " takes degrees C (a sensor's mV or ohm only with `plc_cell test`)");
    sensor_msgs::Temperature m;
    {
      std::lock_guard<std::mutex> lk(link_.mu_);
      const uint64_t next = link_.scanned_ ? link_.last_t_us_ + link_.period_us_ : 0;
      m.header.stamp.fromNSec((link_.t0_us_ + next) * 1000);
      ++link_.inputs_sent_;
    }
    m.temperature = v.has_unit ? v.quantity.value : v.number;
    it->second.publish(m);
    return;
  }
  if (p.kind != Probe::Kind::Address) throw Error(check(p, true));
  const Address a = link_.config_.resolve(p.name);
  if (a.area != Area::X || a.width != Width::Bit) {
    write(p, v);  // a held value of an internal point is a write
    return;
  }
  const auto it = link_.input_pubs_.find(a.index);
  if (it == link_.input_pubs_.end())
    throw Error(p.text + " has no input topic on plc_node: name it in the cell YAML's signals: (plc_node subscribes "
                         "~inputs_stamped/<name> for each named input)");
  Signal m;
  {
    std::lock_guard<std::mutex> lk(link_.mu_);
    const uint64_t next = link_.scanned_ ? link_.last_t_us_ + link_.period_us_ : 0;
    m.header.stamp.fromNSec((link_.t0_us_ + next) * 1000);
    ++link_.inputs_sent_;
  }
  m.data = v.number != 0;
  it->second.publish(m);
}

void RosTarget::write(const Probe& p, const Value& v) {
  if (p.kind != Probe::Kind::Address) throw Error(check(p, true));
  WriteMemory srv;
  srv.request.address = p.name;
  if (p.format == ValueFormat::F32) {
    const float f = float(v.number);
    uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    srv.request.values.push_back(bits);
  } else {
    srv.request.values.push_back(std::llround(v.number));
  }
  if (!ros::service::call(link_.node_ + "/write", srv)) throw Error("plc_node " + link_.node_ + ": ~write failed");
  if (!srv.response.success) throw Error(srv.response.message);
}

void RosTarget::force(const Probe& p, bool on) {
  ForceDiscrete srv;
  srv.request.address = p.name;
  srv.request.value = on;
  if (!ros::service::call(link_.node_ + "/force", srv)) throw Error("plc_node " + link_.node_ + ": ~force failed");
  if (!srv.response.success) throw Error(srv.response.message);
}

void RosTarget::release(const Probe* p) {
  ReleaseDiscrete srv;
  srv.request.address = p ? p->name : "";
  if (!ros::service::call(link_.node_ + "/release", srv)) throw Error("plc_node " + link_.node_ + ": ~release failed");
  if (!srv.response.success) throw Error(srv.response.message);
}

void RosTarget::simulate(const Probe* p) {
  SimulateInputs srv;
  if (p) srv.request.inputs.push_back(p->name);
  if (!ros::service::call(link_.node_ + "/simulate", srv)) throw Error("plc_node " + link_.node_ + ": ~simulate failed");
  if (!srv.response.success) throw Error(srv.response.message);
}

std::string RosTarget::fault() {
  std::lock_guard<std::mutex> lk(link_.mu_);
  return link_.have_progress_ ? link_.progress_.fault : "";
}

}  // namespace scenario
}  // namespace plc_cell
