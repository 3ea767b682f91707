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

struct AxisDef {
  bool used = false;
  std::string name;            // JointState name; default "pso<n>"
  OutputMode mode = OutputMode::PR;
  bool rotary = false;         // JointState position in rad (rotary) or m (linear)
  double units_per_pulse = 1;  // JointState units per pulse
  std::vector<SwitchDef> switches;
  // Written into the registers at each STOP -> RUN (what an MMI would load):
  bool has_table = false;
  Address table_at{};          // table: {at: R0, text: ...} (text form, parsed at load)
  Table table;
  bool has_params = false;
  Address params_at{};         // params: {at: R2000, p8: 100, ...} (defaults + these)
  AxisParams params;
};

// axes: gp0 / gp1: a FUN147 table written at each STOP -> RUN (table: {at:, text:}).
struct GroupDef {
  bool has_table = false;
  Address table_at{};
  LinTable table;
};

struct AxesConfig {
  std::array<AxisDef, 4> axes;
  std::array<GroupDef, 2> groups;
};

// Throws SourceError (file:line:column) on a bad key or value.
AxesConfig parse_axes_config(const YAML::Node& axes, const std::string& file);

}  // namespace motion
}  // namespace plc_cell
