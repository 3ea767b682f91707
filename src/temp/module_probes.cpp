#include "plc_cell/temp/module_probes.h"

#include <cmath>

#include "plc_cell/core/error.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace temp {
namespace {

// What a scenario step may write for the two families (docs/testing-your-cell.md): a
// sensor's signal in the units of sensor_signal.h, and a temperature read in degrees C.
const ProbeFamilyRegistration temperature_probes{ProbeFamily{
    "temperature",
    "a temperature channel",
    {{"C", {"C", "degC", "\u00b0C"}}, {"mV", {"mV"}}, {"ohm", {"ohm", "\u03a9"}}, {"ohm", {"kohm", "k\u03a9"}, 1000}},
    {"C", "degC", "\u00b0C"}}};
const ProbeFamilyRegistration analog_probes{ProbeFamily{"analog", "an analog input", {{"V", {"V"}}, {"mA", {"mA"}}}, {}}};

Quantity quantity_of(const ProbeInput& v) {
  Quantity q{v.value, Unit::Celsius};
  for (Unit u : {Unit::Celsius, Unit::Millivolt, Unit::Ohm, Unit::Volt, Unit::Milliamp})
    if (v.unit == unit_name(u)) q.unit = u;
  return q;
}

}  // namespace

std::string ModuleProbes::check(Plc&, const ProbeRef& p, bool writing) const {
  if (p.family == "temperature") {
    if (!cell_ || cell_->channel_index(p.name) < 0)
      return "no temperature channel named '" + p.name + "' in the cell's modules";
    return "";
  }
  if (!writing) return p.text + ": an analog input is driven, not read (read its register, R3840...)";
  if (!cell_ || !cell_->analog()) return "the cell has no analog modules (modules.analog)";
  return "";
}

ProbeReading ModuleProbes::read(Plc& plc, const ProbeRef& p) const {
  ProbeReading r;
  if (p.family != "temperature") {
    r.valid = false;
    r.text = "?";
    return r;
  }
  const int ch = cell_ ? cell_->channel_index(p.name) : -1;
  const ChannelReading c = plc.locked([&](ScanEngine&, Memory& m) {
    return ch < 0 ? ChannelReading{} : cell_->readings(m)[size_t(ch)];
  });
  r.valid = ch >= 0 && !c.broken && std::isfinite(c.celsius);
  r.number = r.valid ? c.celsius : 0;
  r.text = r.valid ? probe_number_text(std::round(c.celsius * 1000) / 1000) + " C" : "NaN (" + c.state() + ")";
  return r;
}

void ModuleProbes::drive(Plc& plc, const ProbeRef& p, const ProbeInput& v) const {
  std::string why;
  const Quantity q = quantity_of(v);
  const bool ok = plc.locked([&](ScanEngine&, Memory&) {
    if (p.family == "analog") {
      if (!cell_) return why = "the cell has no analog modules (modules.analog)", false;
      return cell_->drive_analog_input(p.name, q, &why);
    }
    const int ch = cell_ ? cell_->channel_index(p.name) : -1;
    if (ch < 0) return why = "no temperature channel named '" + p.name + "'", false;
    return cell_->drive_channel(size_t(ch), q, &why);
  });
  if (!ok) throw Error(p.text + ": " + why);
}

}  // namespace temp
}  // namespace plc_cell
