#pragma once
// The scenario_runner in wall-clock time (~real_time: true; docs/testing-on-hardware.md, "The
// same cell on ROS"): a scenario's cases on plc_node in real time, or on fatek_bridge /
// tri_bridge in front of a real PLC, through the topics and services a robot stack uses,
// under the rules of `plc_cell test --target`: the file must allow the target ("ros:" and
// the node's name), every refusal is said at file:line before anything is written, the
// resolution is measured and windows tighter than it refused or widened within the
// tolerance, and every case leaves the PLC as it found it.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/ros/topic_plc.h"
#include "plc_cell/scenario/resolution.h"
#include "plc_cell/scenario/restore.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/wall_clock.h"
#include "plc_cell/scenario/wall_clock_target.h"

namespace plc_cell {
namespace scenario {

struct RealTimeOutcome {
  CaseResult result;
  RestoreResult restore;
  uint64_t polls = 0;
};

// A scenario's cases in wall-clock time on what the runner reaches: one node
// (RealTimeRun) or a line of them (scenario_line_real_time.h).
class RealTimeCases {
 public:
  virtual ~RealTimeCases() = default;
  virtual const std::string& target() const = 0;  // "ros:/cell/plc_node"
  virtual const Resolution& resolution() const = 0;
  // Every refusal of the file, one per line ("" when every case can run).
  virtual const std::string& refusals() const = 0;
  // The case of this name (as the file gives it), then every point it touched put back.
  virtual RealTimeOutcome run(const Case& c) = 0;
  // Whether the nodes say which points are forced (then not_as_found() can tell).
  virtual bool says_forced() const = 0;
  // After the cases: each point they touch that is not forced as it was before the first
  // ("X3 (part_present): forced, found not forced"); empty when none.
  virtual std::vector<std::string> not_as_found() = 0;
};

// Waits up to d; true once stop is set (at once, without waiting the rest of d).
bool pause_or_stop(const std::atomic<int>* stop, std::chrono::microseconds d);
// "SIGINT", "SIGTERM", "signal 1".
std::string signal_text(int signo);
// Restore options that retry while what ("plc_node /cell/plc_node") is not answering, and say so.
RestoreOptions restore_retrying(const std::string& what);

// The case of cases with this name; throws Error when there is none.
const Case& case_named(const std::vector<Case>& cases, const std::string& name);
// How a run's wall-clock targets poll (every resolution.period_us) and stop (when stop is set).
WallClockOptions run_options(const Resolution& resolution, const std::string& target, const std::atomic<int>* stop);

// Each point of before found forced that plc no longer has as found, or the words for a
// plc that stopped saying which points are forced.
std::vector<std::string> not_forced_as_found(LinkedPlc& plc, const std::vector<FoundPoint>& before);

class RealTimeRun : public RealTimeCases {
 public:
  // node: resolved; kind: what runs there ("plc_node", "fatek_bridge", "tri_bridge"). stop:
  // set (by a signal handler) when the run must end; the case ends there and is restored.
  // Connects, measures the resolution and checks every case. Throws Error when the node
  // cannot be reached.
  RealTimeRun(const Scenario& sc, const CellConfig& config, uint64_t scan_us, const std::string& node,
              const std::string& kind, double timeout_s, uint64_t tolerance_us, const std::atomic<int>* stop);

  const std::string& target() const override { return target_; }  // "ros:/cell/plc_node"
  // "scenario_runner on plc_node /cell/plc_node (ros:/cell/plc_node): forces ...; writes ..."
  const std::string& banner() const { return banner_; }
  const Resolution& resolution() const override { return resolution_; }
  const std::string& refusals() const override { return refusals_; }
  const std::vector<StepNote>& widened() const { return widened_; }

  RealTimeOutcome run(const Case& c) override;
  bool says_forced() const override { return plc_->says_forced(); }
  std::vector<std::string> not_as_found() override { return not_forced_as_found(*plc_, before_); }

 private:
  const CellConfig& config_;
  std::string target_, banner_, refusals_;
  std::unique_ptr<TopicPlc> plc_;
  Resolution resolution_;
  std::vector<Case> cases_;  // as run: windows widened
  std::vector<StepNote> widened_;
  std::vector<FoundPoint> before_;  // every touched point, before the first case
  const std::atomic<int>* stop_;
};

}  // namespace scenario
}  // namespace plc_cell
