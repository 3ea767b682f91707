// The cell YAML's `stepspeed:` form of an axis ramp.
#include "plc_cell/motion/step_speed.h"

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/address.h"
#include "plc_cell/core/area.h"

namespace plc_cell {
namespace motion {

StepSpeed parse_step_speed(const YamlReader& r, const YAML::Node& v, const std::string& key) {
  if (!v.IsMap()) r.fail(v, key, "expected {pps: 1-10000, accel_steps: n, done: Mn}");
  StepSpeed s;
  s.used = true;
  s.line = YamlReader::line(v);
  for (const auto& f : v) {
    const std::string k = f.first.as<std::string>();
    const YAML::Node& x = f.second;
    if (k == "pps") {
      s.pps = r.integer(x, key + ".pps", INT64_MIN, INT64_MAX);
      if (s.pps < 1 || s.pps > kStepMaxPps) r.fail(x, key + ".pps", "expected a whole number 1-10000 (pulses/s)");
    } else if (k == "accel_steps") {
      s.accel_steps = r.integer(x, key + ".accel_steps", INT64_MIN, INT64_MAX);
      if (s.accel_steps < 1 || s.accel_steps > kStepMaxAccel)
        r.fail(x, key + ".accel_steps", "expected a whole number 1-2147483647 (steps from standstill to pps)");
    } else if (k == "done") {
      Address a;
      std::string why;
      // The special relays (M1912 on) belong to the PLC itself.
      if (!try_parse_address(r.str(x, key + ".done"), &a, &why) || a.area != Area::M || a.width != Width::Bit ||
          a.index >= special::kFirstSpecialM)
        r.fail(x, key + ".done", "expected a relay M0-M1911");
      s.done = static_cast<int>(a.index);
    } else {
      r.fail(f.first, key + "." + k, "unknown (pps, accel_steps, done)");
    }
  }
  if (s.pps == 0) r.fail(v, key, "needs pps (1-10000)");
  if (s.accel_steps == 0) r.fail(v, key, "needs accel_steps");
  return s;
}

}  // namespace motion
}  // namespace plc_cell
