#include "plc_cell/motion/axis_probes.h"

#include "plc_cell/motion/motion_unit.h"

namespace plc_cell {
namespace motion {
namespace {

int axis_number(const MotionUnit& u, const std::string& name) {
  for (int n = 0; n < kAxes; ++n)
    if (u.config().axes[size_t(n)].used && u.config().axes[size_t(n)].name == name) return n;
  return -1;
}

}  // namespace

std::string AxisProbes::check(Plc& plc, const ProbeRef& p, bool) const {
  return plc.locked([&](ScanEngine&, Memory&) { return axis_number(*unit_, p.name); }) >= 0
             ? ""
             : "no axis named '" + p.name + "' in the cell's axes";
}

ProbeReading AxisProbes::read(Plc& plc, const ProbeRef& p) const {
  struct Axis {
    int64_t pulses;
    double hz;
    int error;
  };
  const Axis x = plc.locked([&](ScanEngine&, Memory&) {
    MotionUnit& u = *unit_;
    const int n = axis_number(u, p.name);
    if (n < 0) return Axis{0, 0, 0};
    return Axis{u.position(n), u.frequency(n) * u.axis(n).direction(), u.error(n)};
  });
  return axis_reading(p.field, x.pulses, x.hz, x.error);
}

ProbeReading axis_reading(const std::string& field, int64_t pulses, double hz, int error) {
  ProbeReading r;
  if (field == "state") {
    r.word = error ? "error" : hz != 0 ? "moving" : "idle";
    r.number = error;
    r.text = error ? "error " + std::to_string(error) : r.word;
    return r;
  }
  r.number = field == "position" ? double(pulses) : hz;
  r.text = probe_number_text(r.number);
  return r;
}

}  // namespace motion
}  // namespace plc_cell
