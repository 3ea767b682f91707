#include "plc_cell/ros/register_topics.h"

#include "plc_cell/RegisterBlock.h"
#include "plc_cell/core/memory.h"
#include "plc_cell/ros/frame_id.h"

namespace plc_cell {

RegisterTopic::RegisterTopic(ros::NodeHandle& pnh, SoftCell& cell, const RegisterGroup& group)
    : cell_(&cell), group_(group), frame_id_(frame_id_param(pnh)) {
  pub_ = pnh.advertise<RegisterBlock>("registers/" + group_.name, 10);
}

void RegisterTopic::publish(const ros::Time& stamp) {
  RegisterBlock msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = frame_id_;
  msg.name = group_.name;
  msg.address = group_.text;
  cell_->plc().locked([&](ScanEngine&, Memory& m) {
    for (const auto& s : group_.spans) {
      Address a = s.start;
      const uint32_t stride = element_stride(a);
      for (uint32_t k = 0; k < s.count; ++k, a.index += stride) msg.values.push_back(m.read(a));
    }
    return 0;
  });
  pub_.publish(msg);
}

void add_register_topics(ros::NodeHandle& pnh, SoftCell& cell, TopicGroups* groups) {
  for (const auto& g : cell.config().registers) groups->add(std::make_unique<RegisterTopic>(pnh, cell, g));
}

}  // namespace plc_cell
