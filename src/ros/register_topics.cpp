#include "plc_cell/ros/register_topics.h"

#include <cmath>

#include "plc_cell/RegisterBlock.h"
#include "plc_cell/core/memory.h"

namespace plc_cell {

RegisterTopics::RegisterTopics(ros::NodeHandle& nh, ros::NodeHandle& pnh, SoftCell& cell, bool virtual_time)
    : cell_(cell) {
  const auto& groups = cell.config().registers;
  topics_.resize(groups.size());  // fixed from here on: the timers keep pointers to the elements
  for (size_t i = 0; i < groups.size(); ++i) {
    Topic& t = topics_[i];
    t.group = groups[i];
    t.period_us = uint64_t(std::llround(1e6 / t.group.rate_hz));
    t.pub = pnh.advertise<RegisterBlock>("registers/" + t.group.name, 10);
    if (!virtual_time)
      t.timer = nh.createTimer(ros::Duration(1.0 / t.group.rate_hz),
                               [this, &t](const ros::TimerEvent&) { publish(t, ros::Time::now()); });
  }
}

void RegisterTopics::after_virtual_scan(uint64_t now_us) {
  for (auto& t : topics_) {
    if (now_us < t.due_us) continue;
    ros::Time stamp;
    stamp.fromNSec(now_us * 1000);
    publish(t, stamp);
    t.due_us = (now_us / t.period_us + 1) * t.period_us;
  }
}

void RegisterTopics::publish(Topic& t, const ros::Time& stamp) {
  RegisterBlock msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = cell_.config().name;
  msg.name = t.group.name;
  msg.address = t.group.text;
  cell_.plc().locked([&](ScanEngine&, Memory& m) {
    for (const auto& s : t.group.spans) {
      Address a = s.start;
      const uint32_t stride = element_stride(a);
      for (uint32_t k = 0; k < s.count; ++k, a.index += stride) msg.values.push_back(m.read(a));
    }
    return 0;
  });
  t.pub.publish(msg);
}

}  // namespace plc_cell
