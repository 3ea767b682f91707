#pragma once
// A line's scenario target made of one target per cell: every name is CELL.NAME and goes to
// its cell's target, which takes it as it would for the cell alone. What a name does on a
// line is said here once; each kind of line says only how it finds a cell's target: in
// virtual time (line/line_target.h), on its PLCs (line_wall_clock_target.h), through ROS
// (ros/scenario_line_link.h).
#include <string>
#include <vector>

#include "plc_cell/scenario/target.h"

namespace plc_cell {
namespace scenario {

class RoutedTarget : public Target {
 public:
  // Why p cannot be read or driven: no cell in its name, a cell the line has not or cannot
  // reach, or its cell's own reason prefixed with the cell ("robot: ...").
  std::string check(const Probe& p, bool writing) override;
  Reading read(const Probe& p) override { return cell_or_throw(p).read(p); }
  void set(const Probe& p, const Value& v) override { cell_or_throw(p).set(p, v); }
  void write(const Probe& p, const Value& v) override { cell_or_throw(p).write(p, v); }
  void force(const Probe& p, bool on) override { cell_or_throw(p).force(p, on); }
  void release(const Probe* p) override;   // nullptr: in every cell
  void simulate(const Probe* p) override;  // nullptr: in every cell
  // "robot.stop_pb (X1)" for a signal; as written when the cell has no other name for it.
  std::string label(const Probe& p) override;

 protected:
  // The target of the line's cell `cell`, or nullptr: then *absent says why when the line
  // has the cell but no target for it (out of reach), and stays empty when it has no such cell.
  virtual Target* target_of(const std::string& cell, std::string* absent) = 0;
  // "infeed, robot, test": every cell of the line, for messages.
  virtual std::string cell_names() const = 0;
  // Every cell's target there is.
  virtual std::vector<Target*> cell_targets() = 0;

  // p's cell's target, or nullptr and why.
  Target* cell_of(const Probe& p, std::string* why);
  Target& cell_or_throw(const Probe& p);
};

}  // namespace scenario
}  // namespace plc_cell
