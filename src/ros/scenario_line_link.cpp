// The scenario_runner's link to a line in virtual time (ros/scenario_line_link.h).
#include "plc_cell/ros/scenario_line_link.h"

#include <algorithm>

#include <rosgraph_msgs/Clock.h>
#include <std_srvs/Trigger.h>

#include "plc_cell/core/error.h"
#include "plc_cell/ros/scenario_line_real_time.h"

namespace plc_cell {
namespace scenario {

LineLink::LineLink(const line::Line& line, const std::string& ns, double timeout_s, bool read_fallback)
    : ns_(ns), timeout_s_(timeout_s), tick_us_(line.tick_us()) {
  wait_for_cells(line, ns, timeout_s);
  for (size_t i = 0; i < line.size(); ++i) {
    const std::string& cell = line.entry(i).name;
    const std::string node = node_of(ns, cell);
    std::string node_cell, node_line;
    bool virtual_time = false;
    if (!ros::param::get(node + "/cell", node_cell))
      throw Error("the cell '" + cell + "' of the line is not running on ROS (no parameter " + node +
                  "/cell within ~timeout): in virtual time one line nodelet or line_node runs every cell of the line");
    ros::param::get(node + "/line", node_line);
    if (real_path(node_line) != real_path(line.file()))
      throw Error(node + " runs a cell of the line " + (node_line.empty() ? "(none)" : node_line) +
                  ", the scenario names " + line.file());
    const CellConfig& config = const_cast<line::Line&>(line).cell(i)->config();
    if (real_path(node_cell) != real_path(config.file))
      throw Error(node + " runs the cell " + node_cell + ", the line file names " + config.file);
    ros::param::get(node + "/virtual_time", virtual_time);
    if (!virtual_time)
      throw Error(node + " runs in real time: a line's scenario in virtual time needs the line nodelet's "
                  "~virtual_time: true (or give the runner ~real_time: true)");
    double lag = 0.1;
    ros::param::get(node + "/virtual_time_lag", lag);
    lag_us_ = uint64_t(lag * 1e6);
    cells_.push_back(std::make_unique<NodeLink>(node, config, line.period_us(i), lag_us_, timeout_s, read_fallback));
    cells_.back()->step_us_ = tick_us_;
    names_.push_back(cell);
    periods_.push_back(line.period_us(i));
  }
}

int LineLink::find(const std::string& cell) const {
  const auto it = std::find(names_.begin(), names_.end(), cell);
  return it == names_.end() ? -1 : int(it - names_.begin());
}

std::string LineLink::names() const {
  std::string s;
  for (const auto& n : names_) s += (s.empty() ? "" : ", ") + n;
  return s;
}

void LineLink::publish_clock(uint64_t t_us) {
  rosgraph_msgs::Clock c;
  c.clock.fromNSec((cells_[0]->t0_us_ + t_us + lag_us_) * 1000);
  clock_pub_.publish(c);
}

void LineLink::call_reset() {
  std_srvs::Trigger srv;
  if (!ros::service::call(ns_ + "/reset", srv))
    throw Error("the line " + ns_ + ": " + ns_ + "/reset could not be called (is its nodelet running?)");
  if (!srv.response.success) throw Error(srv.response.message);
}

void LineLink::start_case(bool counted) {
  uint64_t next = 0;
  for (const auto& c : cells_) next = std::max(next, c->next_t0());
  const uint64_t t0 = (next + tick_us_ - 1) / tick_us_ * tick_us_;
  for (auto& c : cells_) c->start_case(t0, counted);
}

void LineLink::connect() {
  if (connected_) return;
  NodeLink& first = *cells_[0];
  std::string clock_topic = "/clock";
  ros::param::get(first.node_ + "/clock_topic", clock_topic);
  clock_pub_ = first.advertise(ros::AdvertiseOptions::create<rosgraph_msgs::Clock>(
      clock_topic, 1000, ros::SubscriberStatusCallback(), ros::SubscriberStatusCallback(), ros::VoidConstPtr(), nullptr));
  for (auto& c : cells_) c->advertise_inputs();
  if (!ros::service::waitForService(ns_ + "/reset", ros::Duration(timeout_s_)))
    throw Error("the line " + ns_ + " has no " + ns_ + "/reset service within " + std::to_string(timeout_s_) +
                " s: is its nodelet running in virtual time (~virtual_time: true)?");
  first.connect_publisher(&clock_pub_, "the line's ~clock_topic");
  for (auto& c : cells_)
    for (auto& p : c->input_pubs_) c->connect_publisher(&p.second, "a named input");
  // As a lone node's link: reset, scan once and see every cell's topics arrive; else again.
  const double attempt_s = std::min(timeout_s_, 3.0);
  std::string why = "no ~virtual_time/scanned message";
  for (int attempt = 0; attempt < 10; ++attempt) {
    start_case(false);
    call_reset();
    bool again = false;
    for (auto& c : cells_) again = c->take_topics(attempt_s) || again;
    if (again) continue;
    publish_clock(0);
    why.clear();
    for (auto& c : cells_)
      if (!c->await_first_scan(attempt_s)) why += (why.empty() ? "" : "; ") + c->missing();
    if (why.empty()) {
      for (auto& c : cells_) c->mark_connected();
      connected_ = true;
      return;
    }
  }
  throw Error("the line " + ns_ + ": a scan's messages did not all arrive (" + why + ")");
}

void LineLink::begin_case() {
  connect();
  start_case(true);
  call_reset();
}

// The clock goes out once every cell has its stamped inputs; a cell that does not scan at t
// is complete at its last scan before it.
void LineLink::scan(uint64_t t_us) {
  for (auto& c : cells_) c->await_inputs();
  publish_clock(t_us);
  for (size_t i = 0; i < cells_.size(); ++i) cells_[i]->await_scan(t_us - t_us % periods_[i]);
  for (auto& c : cells_) c->stepped(t_us);
}

// ---- LineRosTarget ----

LineRosTarget::LineRosTarget(LineLink& link) : link_(link) {
  link_.begin_case();
  for (size_t i = 0; i < link_.size(); ++i) cells_.push_back(std::make_unique<RosTarget>(link_.cell(i), false));
}

Target* LineRosTarget::target_of(const std::string& cell, std::string*) {
  const int i = link_.find(cell);
  return i < 0 ? nullptr : cells_[size_t(i)].get();
}

std::vector<Target*> LineRosTarget::cell_targets() {
  std::vector<Target*> out;
  for (auto& c : cells_) out.push_back(c.get());
  return out;
}

std::string LineRosTarget::fault() {
  for (size_t i = 0; i < cells_.size(); ++i) {
    const std::string f = cells_[i]->fault();
    if (!f.empty()) return link_.name(i) + ": " + f;
  }
  return "";
}

}  // namespace scenario
}  // namespace plc_cell
