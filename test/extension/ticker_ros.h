#pragma once
// The ROS side of the made-up ticker extension (ticker_extension.h), written as a subsystem's
// side is (src/ros/counter_topics.cpp): a TopicGroup publishing ~ticker/count
// (std_msgs/Int64), registered under the extension's name.
#include <std_msgs/Int64.h>

#include "plc_cell/ros/extension_ros.h"
#include "ticker_extension.h"

namespace ticker {

class Topics : public TopicGroup {
 public:
  Topics(ros::NodeHandle& pnh, SoftCell& cell) : cell_(&cell) { pub_ = pnh.advertise<std_msgs::Int64>("ticker/count", 10); }
  double rate_hz() const override { return 100; }
  void publish(const ros::Time&) override {
    std_msgs::Int64 m;
    m.data = cell_->plc().locked([&](ScanEngine&, Memory&) { return cell_->get<State>()->ticks; });
    pub_.publish(m);
  }
  std::vector<std::string> topics() const override { return {pub_.getTopic()}; }
  void rebind(SoftCell& cell) override { cell_ = &cell; }
  std::string layout(SoftCell&) const override { return "ticker count\n"; }

 private:
  SoftCell* cell_;
  ros::Publisher pub_;
};

// The one registration line of its ROS side.
struct RosRegistration {
  RosSideRegistration side{"ticker", [](RosSideContext& c, TopicGroups* groups) {
                             groups->add(std::make_unique<Topics>(c.pnh, c.cell));
                           }};
};

}  // namespace ticker
