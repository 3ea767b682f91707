#pragma once
// The scenario_runner in wall-clock time (~real_time: true; docs/testing-on-hardware.md, "The
// same cell on ROS"): a scenario's cases on plc_node in real time, or on fatek_bridge /
// tri_bridge in front of a real PLC, through the topics and services a robot stack uses,
// under the rules of `plc_cell test --target`: the file must allow the target ("ros:" and
// the node's name), every refusal is said at file:line before anything is written, the
// resolution is measured and windows tighter than it refused or widened within the
// tolerance, and every case leaves the PLC as it found it.
#include <atomic>
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

namespace plc_cell {
namespace scenario {

struct RealTimeOutcome {
  CaseResult result;
  RestoreResult restore;
  uint64_t polls = 0;
};

class RealTimeRun {
 public:
  // node: resolved; kind: what runs there ("plc_node", "fatek_bridge", "tri_bridge"). stop:
  // set (by a signal handler) when the run must end; the case ends there and is restored.
  // Connects, measures the resolution and checks every case. Throws Error when the node
  // cannot be reached.
  RealTimeRun(const Scenario& sc, const CellConfig& config, uint64_t scan_us, const std::string& node,
              const std::string& kind, double timeout_s, uint64_t tolerance_us, const std::atomic<int>* stop);

  const std::string& target() const { return target_; }  // "ros:/cell/plc_node"
  // "scenario_runner on plc_node /cell/plc_node (ros:/cell/plc_node): forces ...; writes ..."
  const std::string& banner() const { return banner_; }
  const Resolution& resolution() const { return resolution_; }
  // Every refusal of the file, one per line ("" when every case can run); what was widened.
  const std::string& refusals() const { return refusals_; }
  const std::vector<StepNote>& widened() const { return widened_; }

  // The case of this name (as the file gives it), then every point it touched put back.
  RealTimeOutcome run(const Case& c);
  // Whether the node says which points are forced (then not_as_found() can tell).
  bool says_forced() const { return plc_->says_forced(); }
  // After the cases: each point they touch that is not forced as it was before the first
  // ("X3 (part_present): forced, found not forced"); empty when none.
  std::vector<std::string> not_as_found();

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
