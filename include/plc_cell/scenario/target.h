#pragma once
// What a scenario runs against: a cell in virtual time, advanced one scan at a time. The
// runner (runner.h) holds the timeline and the checks; a target only scans, reads and
// drives. Two exist in virtual time: the cell in process (cell_target.h, for `plc_cell
// test`) and plc_node through its topics and services (the scenario_runner rostest node),
// so one scenario file checks the same expectations on both; and a PLC over a link in
// wall-clock time (wall_clock_target.h), where a "scan" is one poll.
#include <cstdint>
#include <string>

#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace scenario {

class Target {
 public:
  virtual ~Target() = default;
  virtual uint64_t period_us() const = 0;
  // Runs the scan at time t_us (0, then one period after the previous). What was applied
  // since the previous scan takes effect in it.
  virtual void scan(uint64_t t_us) = 0;
  // The instant, from the case's start, that the last scan's state belongs to: t_us in
  // virtual time; on a wall clock (wall_clock_target.h) when its poll went out, which may be
  // later than t_us when the link fell behind. The runner's time follows it.
  virtual uint64_t scanned_at(uint64_t t_us) const { return t_us; }
  // Why the target cannot read (writing false) or drive (writing true) p, or "" if it can:
  // an unknown signal, counter, axis or channel, a probe this target has no way to see.
  virtual std::string check(const Probe& p, bool writing) = 0;
  // The value as the last scan left it (before the first scan: the initial state).
  virtual Reading read(const Probe& p) = 0;
  // Each takes effect before the next scan; a refusal throws plc_cell::Error saying why.
  virtual void set(const Probe& p, const Value& v) = 0;    // terminal or stimulus, held
  virtual void write(const Probe& p, const Value& v) = 0;  // memory, once (as a client)
  virtual void force(const Probe& p, bool on) = 0;
  virtual void release(const Probe* p) = 0;  // nullptr: every forced point
  // The cell's simulation plays input p again (nullptr: every input it has a signal for);
  // an input it has no signal for is refused.
  virtual void simulate(const Probe* p) = 0;
  // How a report names p (probe_label: "stop_pb (X1)"); as written when the target has no
  // cell config to look it up in.
  virtual std::string label(const Probe& p) { return p.text; }
  // Non-empty once the PLC stopped on a fault: the case ends there.
  virtual std::string fault() = 0;
  // How far apart in time the values of one reading may be, as seen so far in the run (read
  // over a round trip, from messages of different ages): a property's violation no longer
  // than this cannot be told from that spread, whatever its grace. 0: one instant (virtual
  // time).
  virtual uint64_t spread_us() { return 0; }
};

}  // namespace scenario
}  // namespace plc_cell
