#pragma once
// What a wire does to a value between its two ends (docs/lines.md, "When a wire
// delivers"), whoever carries it: the line in one process, or a ROS topic between two.
//
// The source end samples its address at the end of each scan (wire_tap.h) and hands on the
// changes, each with the instant of its scan. The delay line turns each into the edges the
// sink end sees, each at its instant in ns:
//   * a plain wire: the value at t + delay, inverted if asked. A scan reads its inputs at
//     its instant, before any cell's outputs of that instant, so a zero delay delivers
//     1 ns after t: the sink's first scan after t sees it, whatever order the cells scan
//     in at t;
//   * a travelling part: each rising edge of the source is a part that reaches the sink
//     after `travel` and covers it for `length` (a sensor the part passes). Parts closer
//     together than their length keep the sensor covered from the first one's arrival to
//     the last one's leaving; any number may be in flight.
#include <cstdint>
#include <vector>

namespace plc_cell {
namespace line {

struct WireModel {
  uint64_t delay_ns = 0;
  bool invert = false;  // a bit only
  bool part = false;    // a bit only: then travel and length instead of delay
  uint64_t travel_ns = 0, length_ns = 0;
};

// The value the sink end sees from t_ns on.
struct WireEdge {
  uint64_t t_ns;
  uint32_t value;
};

class DelayLine {
 public:
  // initial: the source's value before the first scan (a cleared output: 0).
  DelayLine(const WireModel& m, uint32_t initial);

  // What the sink holds before the first delivery: the source's first value through the
  // wire (an inverted wire's sink starts ON; a part's sensor starts uncovered).
  uint32_t initial() const { return initial_; }
  // The source's value sampled at the end of its scan at t_us; appends to out the edges it
  // brings, in time order (none when the value is the one sampled before).
  void sample(uint64_t t_us, uint32_t value, std::vector<WireEdge>* out);

 private:
  uint32_t out(uint32_t v) const { return m_.invert ? uint32_t(v == 0) : v; }

  WireModel m_;
  uint32_t last_;              // the last value sampled
  uint32_t initial_;
  uint64_t covered_until_ns_;  // a part: when the last part leaves the sensor (0: none yet)
};

}  // namespace line
}  // namespace plc_cell
