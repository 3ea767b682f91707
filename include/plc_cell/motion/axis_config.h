#pragma once
// The cell YAML's `axes:` section: per pulse output PSO0-PSO3 its name, output
// mode, mechanics (units per pulse, linear or rotary) and simulated switches at
// axis positions (DOG, limits, PG0), docs/motion.md "Cell YAML".
#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/address.h"
#include "plc_cell/motion/lin_table.h"
#include "plc_cell/motion/params.h"
#include "plc_cell/motion/step_speed.h"
#include "plc_cell/motion/table.h"

namespace plc_cell {
namespace motion {

// An input X0-X255 that the axis position drives: on while from <= pos <= to
// (window), or for `width` pulses of every `period` from `offset` (PG0).
struct SwitchDef {
  int x = 0;
  int64_t from = std::numeric_limits<int64_t>::min() / 4;
  int64_t to = std::numeric_limits<int64_t>::max() / 4;
  int64_t period = 0, offset = 0, width = 1;
  bool level(int64_t pos) const;
  // The next position after pos, moving in dir (+1/-1), where the level changes;
  // INT64_MIN when none.
  int64_t next_change(int64_t pos, int dir) const;
};

enum class OutputMode : uint8_t { UD, PR, AB };
// Idle level of the pulse-carrying pins (U, D, P, A, B); the P/R direction pin is a
// level, ON = up, and is not inverted (docs/motion.md "Pulse pins").
enum class Polarity : uint8_t { NormalOff, NormalOn };

// An incremental encoder on the axis's load: phases A (and B) on inputs X0-X15,
// `periods` A/B periods per output pulse (A leads B when the pulse count rises).
struct EncoderDef {
  bool used = false;
  int a = -1, b = -1;
  int64_t periods = 1;
  int line = 0;  // where it was configured, for errors found when it is attached
};

struct AxisDef {
  bool used = false;
  std::string name;            // JointState name; default "pso<n>"
  OutputMode mode = OutputMode::PR;
  bool has_output = false;     // `output:` given: Y(2n), Y(2n+1) belong to the pulse generator
  Polarity polarity = Polarity::NormalOff;
  // `wiring: {Y0: X0, Y1: X1}`: the output pins looped back to inputs X0-X15
  // (-1: that pin is not wired), e.g. into a counter to check the pulses.
  int wired[2] = {-1, -1};
  int wiring_line = 0;
  EncoderDef encoder;
  bool rotary = false;         // joint_states in rad (rotary) or m (linear)
  double units_per_pulse = 1;  // user units (AxisStatus.position, the run action) per pulse
  // m (linear) or rad (rotary) per pulse, for joint_states (REP 103: SI units); 0 = not
  // given: units_per_pulse, the user unit taken to be m or rad.
  double si_per_pulse = 0;
  double joint_scale() const { return si_per_pulse > 0 ? si_per_pulse : units_per_pulse; }
  std::vector<SwitchDef> switches;
  // Written into the registers at each STOP -> RUN (what an MMI would load):
  bool has_table = false;
  Address table_at{};          // table: {at: R0, text: ...} (text form, parsed at load)
  Table table;
  // params: {p8: 100, ...} (defaults + these): the axis's FUN141 parameters from the
  // start; with at: also written there at each STOP -> RUN for a ladder MPARA.
  bool has_params = false;
  bool params_image = false;   // at: given
  Address params_at{};
  AxisParams params;
  // `stepspeed:` the ramp in steps instead of FUN141's P4/P5/P8/P12 (step_speed.h).
  StepSpeed stepspeed;
};

// axes: gp0 / gp1: a FUN147 table written at each STOP -> RUN (table: {at:, text:}).
struct GroupDef {
  bool has_table = false;
  Address table_at{};
  LinTable table;
};

struct AxesConfig {
  std::array<AxisDef, 4> axes;
  std::string file;  // for errors found when the wiring is attached
  std::array<GroupDef, 2> groups;
};

// Throws SourceError (file:line:column) on a bad key or value.
AxesConfig parse_axes_config(const YAML::Node& axes, const std::string& file);

}  // namespace motion
}  // namespace plc_cell
