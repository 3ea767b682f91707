#pragma once
// What the parts of `plc_cell test --target` share (target_run.cpp: the run; target_case.cpp:
// one case and its restore).
#include <chrono>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "plc_cell/io/stop_signal.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/scenario/linked_plc.h"
#include "plc_cell/scenario/resolution.h"
#include "plc_cell/scenario/restore.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace cli {

struct FileRun {
  const scenario::Scenario* sc = nullptr;
  std::unique_ptr<Cell> cell;          // built to check: its config and program
  std::vector<scenario::Case> cases;   // those -k selects, their windows as run
};

struct TargetRun {
  std::string target;  // --target as given
  std::unique_ptr<scenario::LinkedPlc> plc;
  std::unique_ptr<StopSignal> stop;
  std::string journal;  // the restore journal's path
  std::chrono::milliseconds restore_for{30000};
  scenario::Resolution resolution;
  std::vector<scenario::StepNote> widened;  // the windows --tolerance widened
  bool run_mode = false;  // the PLC was seen in RUN
  std::string record_dir;  // --record; "" = none
  std::set<std::string> recorded;

  std::string why_stopped() const;
};

struct CaseRun {
  scenario::CaseResult result;
  scenario::RestoreResult restore;
  size_t touched = 0;     // points the case wrote, forced or released
  uint64_t polls = 0, slowest_us = 0;
  bool stopped = false;   // by a signal: no case runs after it
};

// Waits up to d; true once SIGINT or SIGTERM has come.
bool wait_or_stop(StopSignal& stop, std::chrono::microseconds d);

// One case: what it touches read first, the case (its line and report printed), then every
// point put back (printed as it goes). A case not put back whole counts as failed.
CaseRun run_case_on_target(TargetRun& run, const FileRun& file, const scenario::Case& c);

// A journal an earlier run on this target left (it was killed before it restored): put back
// first. False, with what is missing printed, when it could not be.
bool restore_left_journal(TargetRun& run);

}  // namespace cli
}  // namespace plc_cell
