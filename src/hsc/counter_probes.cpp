#include "plc_cell/hsc/counter_probes.h"

#include "plc_cell/hsc/hsc_unit.h"

namespace plc_cell {
namespace hsc {
namespace {

int counter_number(const HscUnit& u, const std::string& name) {
  const auto& cs = u.config().counters;
  for (size_t n = 0; n < cs.size(); ++n)
    if (cs[n].used && cs[n].name == name) return int(n);
  return -1;
}

// "X4" -> 4 if X4 is a measured input, else -1.
int pulse_input(const HscUnit& u, const std::string& name) {
  for (int x : u.config().pulse.inputs)
    if (name == "X" + std::to_string(x)) return x;
  return -1;
}

}  // namespace

std::string CounterProbes::check(Plc& plc, const ProbeRef& p, bool writing) const {
  if (p.family == "counter")
    return plc.locked([&](ScanEngine&, Memory&) { return counter_number(*unit_, p.name); }) >= 0
               ? ""
               : "no counter named '" + p.name + "' in the cell's counters";
  if (writing) return p.text + ": a pulse measurement is read, not driven";
  return plc.locked([&](ScanEngine&, Memory&) { return pulse_input(*unit_, p.name); }) >= 0
             ? ""
             : p.name + " is not measured (counters.pulse_measurement.inputs)";
}

ProbeReading CounterProbes::read(Plc& plc, const ProbeRef& p) const {
  ProbeReading r;
  if (p.family == "counter") {
    r.number = double(plc.locked([&](ScanEngine&, Memory&) {
      const int n = counter_number(*unit_, p.name);
      return n < 0 ? int64_t(0) : unit_->count(n);
    }));
  } else {
    // As ~pulses/Xn shows it: width and period in the configured unit, frequency in Hz.
    r.number = plc.locked([&](ScanEngine&, Memory&) {
      const int x = pulse_input(*unit_, p.name);
      if (x < 0) return 0.0;
      const PulseReading m = unit_->pulse(x);
      return p.field == "frequency" ? m.frequency_hz
                                    : unit_->config().pulse.in_unit(p.field == "width" ? m.width_ns : m.period_ns);
    });
  }
  r.text = probe_number_text(r.number);
  return r;
}

}  // namespace hsc
}  // namespace plc_cell
