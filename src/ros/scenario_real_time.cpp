// The scenario_runner in wall-clock time (ros/scenario_real_time.h): the same wall-clock
// target, rules and restore as `plc_cell test --target`, on a node's topics and services.
#include "plc_cell/ros/scenario_real_time.h"

#include <time.h>

#include <algorithm>
#include <csignal>

#include <iostream>

#include "plc_cell/core/error.h"
#include "plc_cell/scenario/wall_clock_target.h"

namespace plc_cell {
namespace scenario {

// Waits up to d; true once the run must stop.
bool pause_or_stop(const std::atomic<int>* stop, std::chrono::microseconds d) {
  const auto end = std::chrono::steady_clock::now() + d;
  for (;;) {
    if (stop && stop->load()) return true;
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(end - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    const long step = long(std::min<int64_t>(left.count(), 10000));  // a stop is seen within 10 ms
    const timespec ts{0, step * 1000};
    ::nanosleep(&ts, nullptr);
  }
}

std::string signal_text(int signo) {
  return signo == SIGINT ? "SIGINT" : signo == SIGTERM ? "SIGTERM" : "signal " + std::to_string(signo);
}

RestoreOptions restore_retrying(const std::string& what) {
  RestoreOptions r;
  r.wait = [](std::chrono::milliseconds d) { return pause_or_stop(nullptr, d); };
  r.waiting = [what](const std::string& why) {
    std::cout << "restore: " << what << " is not answering (" << why << "); trying again\n" << std::flush;
  };
  return r;
}

RealTimeRun::RealTimeRun(const Scenario& sc, const CellConfig& config, uint64_t scan_us, const std::string& node,
                         const std::string& kind, double timeout_s, uint64_t tolerance_us,
                         const std::atomic<int>* stop)
    : config_(config), target_("ros:" + node), cases_(sc.cases), stop_(stop) {
  plc_ = std::make_unique<TopicPlc>(node, kind, config.signals, timeout_s);
  banner_ = "scenario_runner on " + plc_->describe() + " (" + target_ + "): " + forces_and_writes(cases_, config);
  std::cout << banner_ << "\n" << std::flush;
  plc_->connect(std::chrono::milliseconds(1000));
  std::vector<Address> polled;
  for (const auto& c : cases_) {
    const WallClockTarget t(*plc_, config, c, {});
    for (const Address& a : t.polled_addresses())
      if (std::find(polled.begin(), polled.end(), a) == polled.end()) polled.push_back(a);
  }
  resolution_ = measure_resolution(*plc_, polled, scan_us);
  std::cout << "connected: resolution " << resolution_.text() << "\n";
  if (!plc_->says_forced())
    std::cout << plc_->describe() << " says not which points are forced (no ~forced, no ~read_forced): what "
                                     "the cases force is released after each, a point found forced included, and "
                                     "whether the PLC holds a force is not read back here\n";
  const WallClockRules rules{plc_->describe(), plc_->cannot_force(), resolution_.us(), tolerance_us};
  std::vector<TouchedPoint> all;
  for (const auto& c : cases_)
    for (const auto& p : touched_points(c, config))
      if (std::none_of(all.begin(), all.end(), [&](const TouchedPoint& t) { return t.address == p.address; }))
        all.push_back(p);
  before_ = read_found(*plc_, all);
  for (const auto& d : refusals_on(*plc_, target_, sc, config, rules, &cases_, &widened_, true))
    refusals_ += d.to_string() + "\n";
  for (const auto& w : widened_) std::cout << w.to_string() << "\n";
  std::cout << std::flush;
}

const Case& case_named(const std::vector<Case>& cases, const std::string& name) {
  const auto it = std::find_if(cases.begin(), cases.end(), [&](const Case& c) { return c.name == name; });
  if (it == cases.end()) throw Error("no case named '" + name + "'");
  return *it;
}

WallClockOptions run_options(const Resolution& resolution, const std::string& target, const std::atomic<int>* stop) {
  WallClockOptions o;
  o.period_us = resolution.period_us;
  o.wait = [stop](std::chrono::microseconds d) { return pause_or_stop(stop, d); };
  o.why_stopped = [stop] { return "stopped by " + signal_text(stop ? stop->load() : 0); };
  o.target_text = target;
  return o;
}

RealTimeOutcome RealTimeRun::run(const Case& named) {
  const Case& c = case_named(cases_, named.name);
  WallClockTarget target(*plc_, config_, c, run_options(resolution_, target_, stop_));
  RealTimeOutcome out;
  out.result = begin_and_run(c, target);
  out.polls = target.polls();
  if (!target.touched().empty())
    out.restore = restore_points(*plc_, target.found(), target.touched(), restore_retrying(plc_->describe()));
  return out;
}

std::vector<std::string> not_forced_as_found(LinkedPlc& plc, const std::vector<FoundPoint>& before) {
  std::vector<Address> bits;
  std::vector<const FoundPoint*> found;
  for (const auto& f : before)
    if (f.forced) bits.push_back(f.point.address), found.push_back(&f);
  std::vector<std::string> out;
  if (bits.empty()) return out;
  const auto now = plc.forced(bits);
  if (!now) return {plc.describe() + " stopped saying which points are forced"};
  const std::vector<uint32_t> values = plc.read(bits);
  for (size_t i = 0; i < found.size(); ++i) {
    const bool was = *found[i]->forced, is = (*now)[i];
    if (was != is)
      out.push_back(found[i]->point.label + ": " + (is ? "forced" : "not forced") + ", found " +
                    (was ? "forced" : "not forced"));
    else if (was && values[i] != found[i]->value)
      out.push_back(found[i]->point.label + ": forced " + (values[i] ? "ON" : "OFF") + ", found forced " +
                    (found[i]->value ? "ON" : "OFF"));
  }
  return out;
}

}  // namespace scenario
}  // namespace plc_cell
