// A PLC on ROS as a wall-clock scenario target's link (ros/topic_plc.h).
#include "plc_cell/ros/topic_plc.h"

#include <algorithm>
#include <thread>

#include "plc_cell/ForceDiscrete.h"
#include "plc_cell/ReadForced.h"
#include "plc_cell/ReadMemory.h"
#include "plc_cell/RegisterBlock.h"
#include "plc_cell/ReleaseDiscrete.h"
#include "plc_cell/Signal.h"
#include "plc_cell/WriteMemory.h"
#include "plc_cell/core/error.h"

namespace plc_cell {
namespace scenario {

namespace {

bool under(const std::string& topic, const std::string& prefix) { return topic.compare(0, prefix.size(), prefix) == 0; }

// "R0, R10:4, DR20": a group's points as its block lists them.
std::vector<std::string> block_points(const std::string& text) {
  std::vector<std::string> out;
  size_t at = 0;
  while (at <= text.size()) {
    const size_t comma = std::min(text.find(',', at), text.size());
    std::string p = text.substr(at, comma - at);
    p.erase(0, p.find_first_not_of(' '));
    p.erase(p.find_last_not_of(' ') + 1);
    if (!p.empty()) out.push_back(p);
    at = comma + 1;
  }
  return out;
}

// The position of a among a group's elements, in the order the block lists them.
bool position_in(const std::vector<RegisterSpan>& spans, const Address& a, size_t* at) {
  size_t i = 0;
  for (const auto& sp : spans) {
    Address e = sp.start;
    for (uint32_t k = 0; k < sp.count; ++k, e.index += element_stride(e), ++i)
      if (e == a) {
        *at = i;
        return true;
      }
  }
  return false;
}

}  // namespace

TopicPlc::TopicPlc(std::string node, std::string kind, std::vector<std::pair<std::string, Address>> signals,
                   double timeout_s)
    : node_(std::move(node)), kind_(std::move(kind)), signals_(std::move(signals)), timeout_s_(timeout_s) {
  for (const auto& s : signals_) signal_values_.push_back({s.second, std::nullopt});
  nh_.setCallbackQueue(&queue_);
  spinner_ = std::make_unique<ros::AsyncSpinner>(1, &queue_);
  spinner_->start();
}

TopicPlc::~TopicPlc() {
  spinner_->stop();
  subs_.clear();
}

void TopicPlc::arrived(const std::string& topic) {
  const ros::WallTime now = ros::WallTime::now();
  const auto it = last_.find(topic);
  if (measuring_ && it != last_.end())
    max_gap_us_ = std::max<uint64_t>(max_gap_us_, uint64_t((now - it->second).toNSec() / 1000));
  last_[topic] = now;
}

void TopicPlc::connect(std::chrono::milliseconds window) {
  const std::string prefix = node_ + "/";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s_);
  // The node advertises its topics one after the other as it starts: they are all there once
  // ~io is and two lists of its topics 100 ms apart are the same.
  ros::master::V_TopicInfo topics;
  std::vector<std::string> mine, before;
  for (;;) {
    topics.clear();
    if (!ros::master::getTopics(topics)) throw Error("the ROS master cannot be reached");
    before = mine;
    mine.clear();
    for (const auto& t : topics)
      if (under(t.name, prefix)) mine.push_back(t.name);
    std::sort(mine.begin(), mine.end());
    if (std::find(mine.begin(), mine.end(), prefix + "io") != mine.end() && mine == before) break;
    if (std::chrono::steady_clock::now() >= deadline)
      throw Error(describe() + " publishes no " + prefix + "io within " + std::to_string(timeout_s_) +
                  " s: is it running?");
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (const auto& t : topics) {
    if (t.name == prefix + "io") {
      subs_.push_back(nh_.subscribe<IoState>(t.name, 100, [this, name = t.name](const IoState::ConstPtr& m) {
        std::lock_guard<std::mutex> lk(mu_);
        io_ = *m;
        have_io_ = true;
        arrived(name);
      }));
    } else if (under(t.name, prefix + "registers/")) {
      subs_.push_back(nh_.subscribe<RegisterBlock>(t.name, 100, [this, name = t.name](const RegisterBlock::ConstPtr& m) {
        std::lock_guard<std::mutex> lk(mu_);
        Group& g = groups_[name];
        if (g.spans.empty()) {  // the block names its points: FBs addresses, or none of use
          try {
            for (const auto& s : block_points(m->address)) g.spans.push_back(parse_register_span(s));
          } catch (const Error&) {
            g.spans.clear();
          }
        }
        g.values.assign(m->values.begin(), m->values.end());
        g.have = true;
        arrived(name);
      }));
    } else if (t.name == prefix + "forced") {
      publishes_forced_ = true;
      subs_.push_back(nh_.subscribe<ForcedPoints>(t.name, 10, [this](const ForcedPoints::ConstPtr& m) {
        std::lock_guard<std::mutex> lk(mu_);
        forced_msg_ = *m;
        forced_stamp_ = m->header.stamp;
      }));
    }
    for (size_t i = 0; i < signals_.size(); ++i)
      if (t.name == prefix + "signals_stamped/" + signals_[i].first)
        subs_.push_back(nh_.subscribe<Signal>(t.name, 100, [this, i](const Signal::ConstPtr& m) {
          std::lock_guard<std::mutex> lk(mu_);
          signal_values_[i].second = m->data;
        }));
  }
  // A node that cannot publish ~forced may read it from the PLC on request (fatek_bridge).
  reads_forced_ = !publishes_forced_ && ros::service::exists(prefix + "read_forced", false);
  for (;;) {
    {
      std::lock_guard<std::mutex> lk(mu_);
      if (have_io_ && (!publishes_forced_ || forced_msg_)) break;
    }
    if (std::chrono::steady_clock::now() >= deadline)
      throw Error(describe() + ": no message on " + prefix + "io (or " + prefix + "forced) within " +
                  std::to_string(timeout_s_) + " s: is it running?");
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  {
    std::lock_guard<std::mutex> lk(mu_);
    measuring_ = true;
  }
  std::this_thread::sleep_for(window);  // the messages that come meanwhile give the gaps
  std::lock_guard<std::mutex> lk(mu_);
  for (const auto& l : last_)  // a topic silent for the whole window: as old as the window at least
    max_gap_us_ = std::max<uint64_t>(max_gap_us_, uint64_t((ros::WallTime::now() - l.second).toNSec() / 1000));
}

bool TopicPlc::from_topics(const Address& a, uint32_t* v) const {
  if ((a.area == Area::X || a.area == Area::Y) && a.width == Width::Bit && a.index < 256) {
    const auto& bits = a.area == Area::X ? io_.x : io_.y;
    *v = a.index < bits.size() && bits[a.index];
    return have_io_;
  }
  for (const auto& s : signal_values_)
    if (s.first == a && s.second) {
      *v = *s.second;
      return true;
    }
  for (const auto& g : groups_) {
    size_t at = 0;
    if (g.second.have && position_in(g.second.spans, a, &at) && at < g.second.values.size()) {
      *v = uint32_t(g.second.values[at]);
      return true;
    }
  }
  return false;
}

template <class Srv>
void TopicPlc::call(const std::string& name, Srv& srv) {
  ros::ServiceClient& client = clients_[name];
  bool called = client.isValid() && client.call(srv);
  if (!called) {
    client = ros::NodeHandle().serviceClient<Srv>(node_ + "/" + name, true);
    called = client.call(srv);
  }
  if (!called) throw CommError(describe() + ": ~" + name + " could not be called (is the node running?)");
  if (!srv.response.success) throw Error(describe() + ": ~" + name + ": " + srv.response.message);
}

uint32_t TopicPlc::read_service(const Address& a) {
  ReadMemory srv;
  srv.request.address = format_address(a);
  srv.request.count = 1;
  call("read", srv);
  if (srv.response.values.empty()) throw Error(describe() + ": ~read " + srv.request.address + " gave no value");
  return uint32_t(srv.response.values[0]);
}

std::vector<uint32_t> TopicPlc::read(const std::vector<Address>& addrs) {
  std::vector<uint32_t> out(addrs.size(), 0);
  std::vector<size_t> missing;
  {
    std::lock_guard<std::mutex> lk(mu_);
    for (size_t i = 0; i < addrs.size(); ++i)
      if (!from_topics(addrs[i], &out[i])) missing.push_back(i);
  }
  for (size_t i : missing) out[i] = read_service(addrs[i]);
  return out;
}

std::optional<std::vector<bool>> TopicPlc::forced(const std::vector<Address>& bits) {
  if (reads_forced_) {
    ReadForced srv;
    for (const Address& b : bits) srv.request.addresses.push_back(format_address(b));
    call("read_forced", srv);
    if (srv.response.forced.size() != bits.size())
      throw Error(describe() + ": ~read_forced answered " + std::to_string(srv.response.forced.size()) + " of " +
                  std::to_string(bits.size()) + " points");
    return std::vector<bool>(srv.response.forced.begin(), srv.response.forced.end());
  }
  // After a change, a ~forced of a later scan says how it went; a change that changed nothing
  // (a point released that was not forced) brings none, and the last one still holds.
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  for (;;) {
    {
      std::lock_guard<std::mutex> lk(mu_);
      if (forced_stamp_ > changed_ || std::chrono::steady_clock::now() >= until) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::lock_guard<std::mutex> lk(mu_);
  if (!forced_msg_) return std::nullopt;
  std::vector<bool> out;
  for (const auto& b : bits) {
    const auto& list = forced_msg_->addresses;
    out.push_back(std::find(list.begin(), list.end(), format_address(b)) != list.end());
  }
  return out;
}

void TopicPlc::write(const Address& a, uint32_t raw) {
  WriteMemory srv;
  srv.request.address = format_address(a);
  srv.request.values.push_back(int64_t(raw));
  call("write", srv);
}

void TopicPlc::force(const Address& bit, bool on) {
  const std::string why = cannot_force();
  if (!why.empty()) throw Error(why);
  ForceDiscrete srv;
  srv.request.address = format_address(bit);
  srv.request.value = on;
  call("force", srv);
  std::lock_guard<std::mutex> lk(mu_);
  changed_ = ros::Time::now();
}

void TopicPlc::unforce(const Address& bit) {
  ReleaseDiscrete srv;
  srv.request.address = format_address(bit);
  call("release", srv);
  std::lock_guard<std::mutex> lk(mu_);
  changed_ = ros::Time::now();
}

std::string TopicPlc::cannot_force() const {
  if (kind_ == "tri_bridge")
    return "tri_bridge holds a point only by writing it again at each poll (the TRi has no DISABLE flag), so the "
           "program and the input refresh still move it between two polls";
  return "";
}

std::optional<RunMode> TopicPlc::mode() {
  std::lock_guard<std::mutex> lk(mu_);
  if (!have_io_) return std::nullopt;
  return io_.run ? RunMode::Run : RunMode::Stop;
}

}  // namespace scenario
}  // namespace plc_cell
