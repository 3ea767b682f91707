#include "plc_cell/ros/topic_group.h"

#include <algorithm>
#include <cmath>

namespace plc_cell {

VirtualRate::VirtualRate(double rate_hz) : period_us_(std::max<uint64_t>(1, uint64_t(std::llround(1e6 / rate_hz)))) {}

bool VirtualRate::due(uint64_t now_us) {
  if (now_us < due_us_) return false;
  due_us_ = (now_us / period_us_ + 1) * period_us_;
  return true;
}

void TopicGroups::add(std::unique_ptr<TopicGroup> group) {
  const double hz = group->rate_hz();
  entries_.push_back(Entry{std::move(group), VirtualRate(hz), ros::Timer(), 0});
}

void TopicGroups::start_timers(ros::NodeHandle& nh) {
  for (auto& e : entries_) {
    TopicGroup* g = e.group.get();  // the timer dies with its entry, before the group
    e.timer = nh.createTimer(ros::Duration(1.0 / g->rate_hz()),
                             [g](const ros::TimerEvent&) { g->publish(ros::Time::now()); });
  }
}

void TopicGroups::after_virtual_scan(uint64_t now_us, bool every_scan) {
  ros::Time stamp;
  stamp.fromNSec(now_us * 1000);
  after_scan(now_us, every_scan, stamp, [](std::function<void()> fn) { fn(); });
}

void TopicGroups::after_scan(uint64_t now_us, bool every_scan, const ros::Time& stamp,
                             const std::function<void(std::function<void()>)>& run) {
  for (auto& e : entries_) {
    if (!e.rate.due(now_us) && !every_scan) continue;
    ++e.published;
    TopicGroup* g = e.group.get();
    run([g, stamp] { g->publish(stamp); });
  }
}

void TopicGroups::count_published(std::vector<std::string>* topics, std::vector<uint64_t>* counts) const {
  for (const auto& e : entries_)
    for (const auto& t : e.group->topics()) {
      topics->push_back(t);
      counts->push_back(e.published);
    }
}

std::string TopicGroups::layout(SoftCell& cell) const {
  std::string out;
  for (const auto& e : entries_) out += e.group->layout(cell);
  return out;
}

void TopicGroups::restart(SoftCell& cell) {
  for (auto& e : entries_) {
    e.group->rebind(cell);
    e.rate = VirtualRate(e.group->rate_hz());
    e.published = 0;
  }
}

}  // namespace plc_cell
