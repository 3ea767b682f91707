// The scenario_runner on a line of cells on ROS (ros/scenario_line_real_time.h).
#include "plc_cell/ros/scenario_line_real_time.h"

#include <ros/ros.h>
#include <stdlib.h>

#include <algorithm>
#include <climits>
#include <iostream>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace scenario {

namespace {

bool named(const LineCellLink& cell, const std::vector<Case>& cases) {
  return !polled_in(cell, cases).empty() || !touched_in(cell, cases).empty();
}

}  // namespace

std::string real_path(const std::string& path) {
  char buf[PATH_MAX];
  return ::realpath(path.c_str(), buf) ? std::string(buf) : path;
}

std::string node_of(const std::string& ns, const std::string& cell) { return ns + "/" + cell + "/plc_node"; }

void wait_for_cells(const line::Line& line, const std::string& ns, double timeout_s) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s);
  for (;;) {
    bool all = true;
    for (size_t i = 0; i < line.size() && all; ++i) all = ros::param::has(node_of(ns, line.entry(i).name) + "/cell");
    if (all || ros::WallTime::now() > deadline || !ros::ok()) return;
    ros::WallDuration(0.1).sleep();
  }
}

LineCellLink LineRealTimeRun::reach(size_t i, const std::string& ns, double timeout_s) {
  LineCellLink link;
  link.name = line_->entry(i).name;
  link.config = &line_->cell(i)->config();
  const std::string node = node_of(ns, link.name);
  std::string node_cell, node_line;
  if (!ros::param::get(node + "/cell", node_cell)) {
    link.absent = "the cell '" + link.name + "' of the line is not running on ROS (no parameter " + node +
                  "/cell within ~timeout: does a line nodelet or line_node run it, its ~cells naming it?)";
    return link;
  }
  ros::param::get(node + "/line", node_line);
  if (real_path(node_line) != real_path(line_->file()))
    throw Error(node + " runs a cell of the line " + (node_line.empty() ? "(none)" : node_line) +
                ", the scenario names " + line_->file());
  if (real_path(node_cell) != real_path(link.config->file))
    throw Error(node + " runs the cell " + node_cell + ", the line file names " + link.config->file);
  plcs_[i] = std::make_unique<TopicPlc>(node, "plc_node", link.config->signals, timeout_s);
  link.plc = plcs_[i].get();
  return link;
}

LineRealTimeRun::LineRealTimeRun(const Scenario& sc, const std::string& ns, double timeout_s, uint64_t tolerance_us,
                                 const std::atomic<int>* stop)
    : target_("ros:" + ns), cases_(sc.cases), stop_(stop) {
  line::LineOptions lo;
  lo.purpose = Cell::Purpose::Check;
  line_ = std::make_unique<line::Line>(sc.line, lo);
  plcs_.resize(line_->size());
  before_.resize(line_->size());
  wait_for_cells(*line_, ns, timeout_s);
  for (size_t i = 0; i < line_->size(); ++i) cells_.push_back(reach(i, ns, timeout_s));
  std::cout << "scenario_runner on the line " << ns << " (" << target_
            << "): " << forces_and_writes_on_line(cells_, cases_) << "\n" << std::flush;
  std::vector<Resolution> rs;
  std::string cannot_force;
  for (size_t i = 0; i < cells_.size(); ++i) {
    LineCellLink& cell = cells_[i];
    if (!cell.plc) continue;
    if (!named(cell, cases_)) {  // not connected: nothing of it is read or written
      cell.plc = nullptr;
      cell.absent = "the cell '" + cell.name + "' is named by no case";
      continue;
    }
    plcs_[i]->connect(std::chrono::milliseconds(1000));
    rs.push_back(measure_resolution(*plcs_[i], polled_in(cell, cases_), line_->cell(i)->scan_period_us()));
    std::cout << cell.name << ": resolution " << rs.back().text() << "\n";
    if (cannot_force.empty()) cannot_force = plcs_[i]->cannot_force();
    says_forced_ = says_forced_ && plcs_[i]->says_forced();
    before_[i] = read_found(*plcs_[i], touched_in(cell, cases_));
  }
  resolution_ = worst_resolution(rs);
  std::cout << "connected: resolution " << resolution_.text() << " (the worst of the cells')\n";
  const WallClockRules rules{"the line " + ns + " on ROS", cannot_force, resolution_.us(), tolerance_us};
  for (const auto& d : refusals_on_line(cells_, target_, sc, rules, &cases_, &widened_))
    refusals_ += d.to_string() + "\n";
  for (const auto& w : widened_) std::cout << w.to_string() << "\n";
  std::cout << std::flush;
}

RealTimeOutcome LineRealTimeRun::run(const Case& named_case) {
  const Case& c = case_named(cases_, named_case.name);
  LineWallClockTarget target(cells_, c, run_options(resolution_, target_, stop_));
  RealTimeOutcome out;
  out.result = begin_and_run(c, target, [&target] { target.begin(); });
  out.polls = target.polls();
  for (size_t i = 0; i < target.size(); ++i) {
    WallClockTarget& t = target.cell(i);
    if (t.touched().empty()) continue;
    const RestoreResult r = restore_points(target.plc(i), t.found(), t.touched(), restore_retrying(target.plc(i).describe()));
    out.restore.restored.insert(out.restore.restored.end(), r.restored.begin(), r.restored.end());
    out.restore.not_restored.insert(out.restore.not_restored.end(), r.not_restored.begin(), r.not_restored.end());
  }
  return out;
}

std::vector<std::string> LineRealTimeRun::not_as_found() {
  std::vector<std::string> out;
  for (size_t i = 0; i < cells_.size(); ++i)
    if (cells_[i].plc)
      for (const auto& w : not_forced_as_found(*cells_[i].plc, before_[i])) out.push_back(w);
  return out;
}

}  // namespace scenario
}  // namespace plc_cell
