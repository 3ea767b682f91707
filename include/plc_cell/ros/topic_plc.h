#pragma once
// A PLC on ROS, read from the topics a robot stack subscribes to and driven through the
// services it calls, as the LinkedPlc of a wall-clock scenario target (scenario/linked_plc.h):
// plc_node in real time, or fatek_bridge / tri_bridge in front of a real PLC, which publish
// the same names (docs/testing-on-hardware.md, "The same cell on ROS"). ~io gives X0-X255
// and Y0-Y255, ~signals_stamped/<name> the cell's named points, ~registers/<group> the
// groups' elements; an address on no topic is read with ~read. Writes go through ~write,
// forces through ~force and ~release; which points are forced is read on ~forced where the
// node publishes it (plc_node), or asked of the PLC by ~read_forced (fatek_bridge). A value
// is as old as the node's last message: the longest gap between its periodic messages,
// measured from the connection on through the whole run, is the link's max_age_us().
#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include "plc_cell/ForcedPoints.h"
#include "plc_cell/IoState.h"
#include "plc_cell/config/register_groups.h"
#include "plc_cell/scenario/linked_plc.h"

namespace plc_cell {
namespace scenario {

class TopicPlc : public LinkedPlc {
 public:
  // node: its resolved name; kind: "plc_node", "fatek_bridge" or "tri_bridge" (what it is
  // decides whether it can hold a point); signals: the cell's names, each read from the
  // node's ~signals_stamped/<name> when it publishes one. timeout_s bounds every wait.
  TopicPlc(std::string node, std::string kind, std::vector<std::pair<std::string, Address>> signals, double timeout_s);
  ~TopicPlc() override;

  // Subscribes the node's topics and waits for its first ~io; then takes `window` to measure
  // how often its periodic topics (~io, ~registers/<group>) come. Throws Error saying what
  // did not come.
  void connect(std::chrono::milliseconds window);

  std::string describe() const override { return kind_ + " " + node_; }
  std::string cannot_reach(const Address&) const override { return ""; }
  std::vector<uint32_t> read(const std::vector<Address>& addrs) override;
  std::optional<std::vector<bool>> forced(const std::vector<Address>& bits) override;
  void write(const Address& a, uint32_t raw) override;
  void force(const Address& bit, bool on) override;
  void unforce(const Address& bit) override;
  std::string cannot_force() const override;
  std::optional<RunMode> mode() override;
  std::string cannot_read_mode() const override { return ""; }
  uint64_t max_age_us() const override {
    std::lock_guard<std::mutex> lk(mu_);
    return max_gap_us_;
  }
  // Whether the node says which points are forced: on ~forced (plc_node), or read from the PLC
  // on request by ~read_forced (fatek_bridge); tri_bridge and modbus_bridge do not.
  bool says_forced() const { return publishes_forced_ || reads_forced_; }

 private:
  struct Group {
    std::vector<RegisterSpan> spans;
    std::vector<int64_t> values;
    bool have = false;
  };
  void arrived(const std::string& topic);  // mu_ held
  bool from_topics(const Address& a, uint32_t* v) const;  // mu_ held
  uint32_t read_service(const Address& a);
  // ~name on a persistent connection (a poll reads often), made again once when it broke.
  template <class Srv>
  void call(const std::string& name, Srv& srv);

  std::string node_, kind_;
  std::vector<std::pair<std::string, Address>> signals_;
  double timeout_s_;
  ros::NodeHandle nh_;
  ros::CallbackQueue queue_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
  std::vector<ros::Subscriber> subs_;
  bool publishes_forced_ = false, reads_forced_ = false;
  std::map<std::string, ros::ServiceClient> clients_;  // by service name; the caller's thread only

  mutable std::mutex mu_;
  IoState io_;
  bool have_io_ = false;
  std::vector<std::pair<Address, std::optional<bool>>> signal_values_;  // per signals_ entry
  std::map<std::string, Group> groups_;                                // by topic
  std::optional<ForcedPoints> forced_msg_;
  // When the last ~force or ~release returned, and the stamp of the last ~forced (its scan's):
  // forced() waits for one stamped after the change, which shows it.
  ros::Time changed_, forced_stamp_;
  std::map<std::string, ros::WallTime> last_;  // a periodic topic's last message
  bool measuring_ = false;
  uint64_t max_gap_us_ = 0;
};

}  // namespace scenario
}  // namespace plc_cell
