#include "plc_cell/scenario/cell_target.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "plc_cell/core/error.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/motion/motion_unit.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace scenario {

namespace {

std::string number_text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

// The raw bits of a value for an address: a bit 0/1, a register's two's complement for a
// negative value, a float's bits for :f32. Throws Error with the address's range.
uint32_t raw(const Address& a, ValueFormat f, const Value& v, const std::string& text) {
  const int bits = value_bits(a);
  if (f == ValueFormat::F32) {
    const float x = float(v.number);
    uint32_t r;
    std::memcpy(&r, &x, sizeof r);
    return r;
  }
  if (v.number != std::floor(v.number)) throw Error(text + ": " + v.text + " is not a whole number");
  const double lo = bits == 1 ? 0 : -std::ldexp(1.0, bits - 1), hi = std::ldexp(1.0, bits) - 1;
  if (v.number < lo || v.number > hi)
    throw Error(text + ": value " + v.text + " out of range " + number_text(lo) + ".." + number_text(hi));
  const int64_t n = int64_t(v.number);
  return uint32_t(n < 0 ? n & (bits == 16 ? 0xFFFF : 0xFFFFFFFFLL) : n);
}

int counter_number(const hsc::HscUnit& u, const std::string& name) {
  const auto& cs = u.config().counters;
  for (size_t n = 0; n < cs.size(); ++n)
    if (cs[n].used && cs[n].name == name) return int(n);
  return -1;
}

// "X4" -> 4 if X4 is a measured input, else -1.
int pulse_input(const hsc::HscUnit& u, const std::string& name) {
  for (int x : u.config().pulse.inputs)
    if (name == "X" + std::to_string(x)) return x;
  return -1;
}

int axis_number(const motion::MotionUnit& u, const std::string& name) {
  for (int n = 0; n < motion::kAxes; ++n)
    if (u.config().axes[size_t(n)].used && u.config().axes[size_t(n)].name == name) return n;
  return -1;
}

}  // namespace

CellTarget::CellTarget(const std::string& cell_yaml, const std::string& program) {
  CellOverrides o;
  o.program = program;
  cell_ = std::make_unique<Cell>(cell_yaml, o, Cell::Purpose::Simulate);
  if (!cell_->plc().set_mode(RunMode::Run)) throw Error("cannot RUN: no program loaded");
}

CellTarget::~CellTarget() = default;

const Address& CellTarget::address(const std::string& name) {
  auto it = addresses_.find(name);
  if (it == addresses_.end()) it = addresses_.emplace(name, cell_->config().resolve(name)).first;
  return it->second;
}

uint64_t CellTarget::period_us() const { return cell_->scan_period_us(); }

void CellTarget::scan(uint64_t t_us) { cell_->plc().scan(t_us); }

std::string CellTarget::check(const Probe& p, bool writing) {
  SoftCell& s = cell_->soft();
  try {
    switch (p.kind) {
      case Probe::Kind::Address: {
        const Address a = cell_->config().resolve(p.name);
        check_format(a, p.format, p.text);
        return "";
      }
      case Probe::Kind::Counter:
        return plc().locked([&](ScanEngine&, Memory&) { return counter_number(s.counters(), p.name); }) >= 0
                   ? ""
                   : "no counter named '" + p.name + "' in the cell's counters";
      case Probe::Kind::AxisPosition:
      case Probe::Kind::AxisState:
      case Probe::Kind::AxisFrequency:
        return plc().locked([&](ScanEngine&, Memory&) { return axis_number(s.motion(), p.name); }) >= 0
                   ? ""
                   : "no axis named '" + p.name + "' in the cell's axes";
      case Probe::Kind::Temperature:
        if (!s.temperature() || s.temperature()->channel_index(p.name) < 0)
          return "no temperature channel named '" + p.name + "' in the cell's modules";
        return "";
      case Probe::Kind::PulseWidth:
      case Probe::Kind::PulsePeriod:
      case Probe::Kind::PulseFrequency:
        if (writing) return p.text + ": a pulse measurement is read, not driven";
        return plc().locked([&](ScanEngine&, Memory&) { return pulse_input(s.counters(), p.name); }) >= 0
                   ? ""
                   : p.name + " is not measured (counters.pulse_measurement.inputs)";
      case Probe::Kind::Analog:
        if (!writing) return p.text + ": an analog input is driven, not read (read its register, R3840...)";
        if (!s.temperature() || !s.temperature()->analog()) return "the cell has no analog modules (modules.analog)";
        return "";
    }
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

Reading CellTarget::read(const Probe& p) {
  SoftCell& s = cell_->soft();
  Reading r;
  switch (p.kind) {
    case Probe::Kind::Address: {
      const Address a = address(p.name);
      const uint32_t v = plc().locked([&](ScanEngine&, Memory& m) { return m.read(a); });
      return address_reading(a, v, p.format);
    }
    case Probe::Kind::Counter:
      r.number = double(plc().locked([&](ScanEngine&, Memory&) {
        const int n = counter_number(s.counters(), p.name);
        return n < 0 ? int64_t(0) : s.counters().count(n);
      }));
      r.text = number_text(r.number);
      return r;
    case Probe::Kind::AxisPosition:
    case Probe::Kind::AxisState:
    case Probe::Kind::AxisFrequency: {
      struct Axis {
        int64_t pulses;
        double hz;
        int error;
      };
      const Axis x = plc().locked([&](ScanEngine&, Memory&) {
        motion::MotionUnit& u = s.motion();
        const int n = axis_number(u, p.name);
        if (n < 0) return Axis{0, 0, 0};
        return Axis{u.position(n), u.frequency(n) * u.axis(n).direction(), u.error(n)};
      });
      if (p.kind == Probe::Kind::AxisPosition) r.number = double(x.pulses);
      if (p.kind == Probe::Kind::AxisFrequency) r.number = x.hz;
      if (p.kind == Probe::Kind::AxisState) {
        // As the axis's status topic shows it: an error code, else pulses going out, else idle.
        r.word = x.error ? "error" : x.hz != 0 ? "moving" : "idle";
        r.number = x.error;
        r.text = x.error ? "error " + std::to_string(x.error) : r.word;
        return r;
      }
      r.text = number_text(r.number);
      return r;
    }
    case Probe::Kind::Temperature: {
      temp::TemperatureCell* tc = s.temperature();
      const int ch = tc ? tc->channel_index(p.name) : -1;
      const temp::ChannelReading c = plc().locked([&](ScanEngine&, Memory& m) {
        return ch < 0 ? temp::ChannelReading{} : tc->readings(m)[size_t(ch)];
      });
      r.valid = ch >= 0 && !c.broken && std::isfinite(c.celsius);
      r.number = r.valid ? c.celsius : 0;
      r.text = r.valid ? number_text(std::round(c.celsius * 1000) / 1000) + " C" : "NaN (" + c.state() + ")";
      return r;
    }
    case Probe::Kind::PulseWidth:
    case Probe::Kind::PulsePeriod:
    case Probe::Kind::PulseFrequency: {
      // As ~pulses/Xn shows it: width and period in the configured unit, frequency in Hz.
      r.number = plc().locked([&](ScanEngine&, Memory&) {
        const hsc::HscUnit& u = s.counters();
        const int x = pulse_input(u, p.name);
        if (x < 0) return 0.0;
        const hsc::PulseReading m = u.pulse(x);
        return p.kind == Probe::Kind::PulseFrequency ? m.frequency_hz
               : u.config().pulse.in_unit(p.kind == Probe::Kind::PulseWidth ? m.width_ns : m.period_ns);
      });
      r.text = number_text(r.number);
      return r;
    }
    case Probe::Kind::Analog:
      break;
  }
  r.valid = false;
  r.text = "?";
  return r;
}

void CellTarget::set(const Probe& p, const Value& v) {
  SoftCell& s = cell_->soft();
  if (p.kind == Probe::Kind::Address) {
    const Address a = address(p.name);
    const uint32_t x = raw(a, p.format, v, p.text);
    if (a.area == Area::X && a.width == Width::Bit) {
      // An input terminal: the scenario plays this sensor from now on, not the simulation.
      plc().locked([&](ScanEngine& e, Memory&) {
        s.simulation().override_input(a.index);
        e.set_input(a.index, x != 0);
        return 0;
      });
      return;
    }
    plc().write(a, {x});
    return;
  }
  std::string why;
  const bool ok = plc().locked([&](ScanEngine&, Memory&) {
    temp::TemperatureCell* tc = s.temperature();
    if (p.kind == Probe::Kind::Analog) {
      if (!tc) return why = "the cell has no analog modules (modules.analog)", false;
      return tc->drive_analog_input(p.name, v.quantity, &why);
    }
    const int ch = tc ? tc->channel_index(p.name) : -1;
    if (ch < 0) return why = "no temperature channel named '" + p.name + "'", false;
    return tc->drive_channel(size_t(ch), v.quantity, &why);
  });
  if (!ok) throw Error(p.text + ": " + why);
}

void CellTarget::write(const Probe& p, const Value& v) {
  if (p.kind != Probe::Kind::Address) throw Error(p.text + ": only an address or signal is written");
  const Address a = address(p.name);
  plc().write(a, {raw(a, p.format, v, p.text)});
}

void CellTarget::force(const Probe& p, bool on) {
  const Address a = address(p.name);
  if (a.width != Width::Bit || !is_discrete(a.area)) throw Error(p.text + ": only a single discrete is forced");
  plc().force(a, ForceAction::Disable);
  plc().force(a, on ? ForceAction::Set : ForceAction::Reset);
}

void CellTarget::release(const Probe* p) {
  std::vector<Address> points;
  if (p) points.push_back(address(p->name));
  else points = plc().locked([](ScanEngine&, Memory& m) { return m.disabled_points(); });
  for (const Address& a : points) plc().force(a, ForceAction::Enable);
}

void CellTarget::simulate(const Probe* p) {
  SoftCell& s = cell_->soft();
  if (!p) {
    plc().locked([&](ScanEngine&, Memory&) {
      for (uint32_t x : s.simulation().simulated_inputs()) s.simulation().resume(x);
      return 0;
    });
    return;
  }
  const Address a = address(p->name);
  if (a.area != Area::X || a.width != Width::Bit) throw Error(p->text + ": only an input (X) is simulated");
  const bool ok = plc().locked([&](ScanEngine&, Memory&) { return s.simulation().resume(a.index); });
  if (!ok) throw Error(p->text + ": the cell's simulation: has no signal on " + format_address(a));
}

std::string CellTarget::fault() {
  return plc().locked([](ScanEngine& e, Memory&) { return e.fault(); });
}

}  // namespace scenario
}  // namespace plc_cell
