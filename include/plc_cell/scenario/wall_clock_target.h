#pragma once
// A PLC over a link as a scenario target, in wall-clock time (docs/testing-on-hardware.md):
// one case's "scan" at t is a poll sent at t after the case's start on the host's monotonic
// clock (or as soon as the previous poll is back, when the link is late: scanned_at() says
// when), reading every address the case reads in as few transactions as the link allows.
// A set of an input locks it (the protocol's force: FATEK's DISABLE, then SET or RESET);
// any other set or write is a write. Before the first poll, begin() reads what the case
// will touch (restore.h); the caller restores it after the case, whatever happened.
#include <chrono>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/scenario/linked_plc.h"
#include "plc_cell/scenario/restore.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/target.h"

namespace plc_cell {
namespace scenario {

// The run was asked to stop (Ctrl-C, SIGTERM): the case ends where it is.
class Stopped : public Error {
 public:
  using Error::Error;
};

struct WallClockOptions {
  uint64_t period_us = 1000;  // one poll per period (the link's round trip)
  // Waits up to d; true when the run is asked to stop (then without waiting).
  std::function<bool(std::chrono::microseconds d)> wait;
  // The failure's words once wait() said stop: "stopped by SIGINT".
  std::function<std::string()> why_stopped = [] { return std::string("stopped"); };
  // After each poll: its instant from the case's start, and the values polled (--record).
  std::function<void(uint64_t t_us, const std::vector<Address>&, const std::vector<uint32_t>&)> polled;
  RestoreJournal* journal = nullptr;
  std::string target_text;  // as the journal names the target
  // In a line (line_wall_clock_target.h): the cell this target is ("robot"); it plans and
  // polls only the names of the case that start with it. "": a lone cell's target.
  std::string cell;
};

class WallClockTarget : public Target {
 public:
  WallClockTarget(LinkedPlc& plc, const CellConfig& config, const Case& c, WallClockOptions opt);

  // Reads what the case will touch (and journals it), then the first poll: the case's time
  // 0. Throws CommError when the link is down, Stopped when asked to stop.
  void begin() {
    find();
    start(std::chrono::steady_clock::now());
  }
  // begin() in its two halves, for targets that share one time 0 (a line's cells, each
  // found first): what the case will touch read, then the first poll with time 0 at `zero`.
  void find();
  void start(std::chrono::steady_clock::time_point zero);
  const std::vector<FoundPoint>& found() const { return found_; }
  // The points the case has written, forced or released so far (what restore_points puts back).
  const std::vector<Address>& touched() const { return touched_; }
  // The addresses each poll reads, in its order.
  const std::vector<Address>& polled_addresses() const { return poll_; }
  uint64_t polls() const { return polls_; }
  uint64_t slowest_poll_us() const { return slowest_us_; }

  uint64_t period_us() const override { return opt_.period_us; }
  void scan(uint64_t t_us) override;
  uint64_t scanned_at(uint64_t) const override { return instant_us_; }
  std::string check(const Probe& p, bool writing) override;
  Reading read(const Probe& p) override;
  void set(const Probe& p, const Value& v) override;
  void write(const Probe& p, const Value& v) override;
  void force(const Probe& p, bool on) override;
  void release(const Probe* p) override;
  void simulate(const Probe* p) override;
  std::string label(const Probe& p) override { return probe_label(p, config_); }
  std::string fault() override { return ""; }
  // A poll period, the slowest round trip and the oldest message seen so far.
  uint64_t spread_us() override { return opt_.period_us + slowest_us_ + plc_.max_age_us(); }

 private:
  Address address(const Probe& p) const;
  uint64_t since_start_us() const;
  void poll();
  void touch(const Address& a);
  // f() on the link; a link failure becomes an Error that says when and what.
  template <class F>
  auto on_link(const char* what, F&& f) -> decltype(f());

  LinkedPlc& plc_;
  const CellConfig& config_;
  WallClockOptions opt_;
  std::string case_name_;
  std::vector<TouchedPoint> points_;
  std::vector<FoundPoint> found_;
  std::vector<Address> touched_;
  std::vector<Address> poll_;
  mutable std::map<std::string, Address> resolved_;  // by probe name
  std::vector<uint32_t> values_;             // the last poll's, in poll_ order
  std::set<std::pair<int, uint32_t>> forced_;  // (area, index) forced by a force step
  std::chrono::steady_clock::time_point start_;
  uint64_t instant_us_ = 0;
  uint64_t polls_ = 0;
  uint64_t slowest_us_ = 0;
};

// begin() on t, then the case (runner.h): a failure before its first step (the link, a
// stop) is the case's failure at its line.
CaseResult begin_and_run(const Case& c, WallClockTarget& t);
// The same for any wall-clock target t whose begin is `begin`.
CaseResult begin_and_run(const Case& c, Target& t, const std::function<void()>& begin);

// Every refusal of sc's cases on plc, each at its file:line once: the file's permission for
// target (as its hardware: key names targets), the names plc cannot reach, the steps and the
// windows the rules refuse and, once connected, the PLC's mode. cases (sc's, or those
// selected) come back with their windows widened; widened says which.
std::vector<Diagnostic> refusals_on(LinkedPlc& plc, const std::string& target, const Scenario& sc,
                                    const CellConfig& config, const WallClockRules& rules, std::vector<Case>* cases,
                                    std::vector<StepNote>* widened, bool connected);

// "forces stop_button (X1), part_present (X3); writes RC0": what cases will force and write.
std::string forces_and_writes(const std::vector<Case>& cases, const CellConfig& config);
// The same of the points the cases touch, as a line gathers them from its cells.
std::string forces_and_writes(const std::vector<TouchedPoint>& points);

// A refusal at the file's hardware: key (its first line when it has none).
Diagnostic at_hardware_key(const Scenario& sc, const std::string& message);
// Why plc cannot run sc's cases in its mode ("the PLC is in STOP; ..."), or "".
std::string mode_refusal(LinkedPlc& plc, const Scenario& sc);

// The refusals, each said once, in file:line order; the same of what was widened.
void said_once(std::vector<Diagnostic>* errors, std::vector<StepNote>* widened);

}  // namespace scenario
}  // namespace plc_cell
