#pragma once
// The properties a monitor watches over the cells it serves (docs/monitor.md,
// "Properties"), as the overview shows them: each property's state now, how often it was
// violated and its last violation. Who evaluates them is above the monitor (a line's run,
// a line's recording: scenario/property_watcher.h); the overview only reads a board.
#include <cstdint>
#include <string>
#include <vector>

namespace plc_cell {
namespace monitor {

// A name of a property and its value at an instant, as text ("robot.in_zone", "ON").
struct NamedValue {
  std::string name, value;
};

struct PropertyStatus {
  std::string text;   // "never: robot.in_zone and test.handler_in_zone"
  std::string where;  // "line.scenario.yaml:10"
  uint64_t within_us = 0;  // its grace: a violation counts once it lasted longer
  bool violated = false;   // now: violated longer than its grace
  uint64_t since_us = 0;   // violated: the instant the violation began
  uint64_t violations = 0;
  // The last violation (violations > 0): the instant it began, how long it lasted (so far,
  // while it goes on) and the values of the property's names at the instant it began.
  uint64_t last_begin_us = 0, last_duration_us = 0;
  bool last_ongoing = false;
  std::vector<NamedValue> last_values;
};

struct PropertyReport {
  std::string source;   // "line.scenario.yaml"
  std::string how;      // "at every scan of every cell of the line"
  uint64_t t_us = 0;    // the last instant evaluated
  bool evaluated = false;  // false: no instant yet
  std::vector<PropertyStatus> properties;
};

class PropertyBoard {
 public:
  virtual ~PropertyBoard() = default;
  // The state after the last instant evaluated; any thread.
  virtual PropertyReport report() const = 0;
  // The state at t_us of a recorded run (its replay cursor); a live board's is report().
  virtual PropertyReport report_at(uint64_t /*t_us*/) const { return report(); }
};

}  // namespace monitor
}  // namespace plc_cell
