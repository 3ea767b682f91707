#include "plc_cell/temp/temperature_cell.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "plc_cell/core/area.h"
#include "plc_cell/core/error.h"
#include "plc_cell/temp/fb_modules.h"
#include "plc_cell/temp/rtd.h"

namespace plc_cell {
namespace temp {
namespace {

// Measurable ranges from the manual (A:6760, A:7214). NTC: none given; plc_cell's -40..150.
void range_of(const ModuleDef& m, double* lo, double* hi) {
  switch (m.sensor) {
    case SensorKind::Pt100: *lo = -200, *hi = 850; return;
    case SensorKind::Pt1000: *lo = -200, *hi = 600; return;
    case SensorKind::Ntc: *lo = -40, *hi = 150; return;
    case SensorKind::Thermocouple: break;
  }
  static const double r[8][2] = {{-200, 900}, {-190, 1300}, {-190, 1000}, {-190, 380},
                                 {0, 1800},   {0, 1700},    {350, 1800},  {-200, 1000}};  // J K E T R S B N
  *lo = r[static_cast<int>(m.tc)][0];
  *hi = r[static_cast<int>(m.tc)][1];
}

// R/D register in the 1xxxx / 2xxxx form of R4004 (used for SR+2 and SR+3 too).
uint16_t encode(const Address& a) { return static_cast<uint16_t>((a.area == Area::R ? 10000 : 20000) + a.index); }

}  // namespace

const TemperatureCell* temperature_cell_of(const ScanEngine* engine) {
  return engine ? engine->extensions().get<TemperatureCell>() : nullptr;
}

TemperatureCell::TemperatureCell(TemperatureConfig cfg, Memory& mem) : cfg_(std::move(cfg)), mem_(mem) {
  if (cfg_.total_channels() > 32) throw Error("more than 32 temperature points (the FBs limit)");
  for (const auto& p : cfg_.plants) {
    plants_.emplace_back(p.params);
    plant_defs_.push_back(p);
  }
  const double res = cfg_.fast ? 1.0 : 0.1;
  for (size_t k = 0; k < cfg_.modules.size(); ++k) {
    const ModuleDef& m = cfg_.modules[k];
    const ModuleInfo& info = module_info(m.kind);
    ModuleState s;
    s.first = channels_.size();
    s.count = info.channels;
    s.slot_us = static_cast<uint64_t>((cfg_.fast ? info.fast_s : info.normal_s) * 1e6) / uint64_t(info.channels);
    modules_.push_back(s);
    for (int c = 0; c < info.channels; ++c) {
      ChannelState ch;
      ch.module = int(k);
      ch.value_c = std::nan("");
      ch.resolution_c = res;
      ch.window.reserve(size_t(cfg_.averaging));
      int plant = -1;
      bool open = true;  // an unwired input reads as a broken line
      if (c < int(m.channels.size())) {
        const ChannelDef& d = m.channels[size_t(c)];
        ch.name = d.name;
        open = d.open;
        for (size_t p = 0; p < plant_defs_.size(); ++p)
          if (plant_defs_[p].name == d.plant) plant = int(p);
      }
      channels_.push_back(ch);
      plant_of_.push_back(plant);
      wired_open_.push_back(open);
    }
  }
  auto plant_c = [this](const std::string& name) {
    ThermalPlant* p = plant(name);
    return p ? p->temperature_c() : 0.0;
  };
  if (cfg_.has_analog) analog_ = std::make_unique<AnalogModules>(cfg_.analog, mem_, plant_c);
  if (cfg_.fb) fb_ = std::make_unique<FbModules>(*cfg_.fb, mem_, plant_c);
}

TemperatureCell::~TemperatureCell() = default;

void TemperatureCell::attached(ScanEngine& e) { e.extensions().attach(this); }
void TemperatureCell::detached(ScanEngine& e) { e.extensions().detach(this); }

ThermalPlant* TemperatureCell::plant(const std::string& name) {
  for (size_t p = 0; p < plants_.size(); ++p)
    if (plant_defs_[p].name == name) return &plants_[p];
  return nullptr;
}

int TemperatureCell::channel_index(const std::string& name) const {
  for (size_t i = 0; i < channels_.size(); ++i)
    if (!name.empty() && channels_[i].name == name) return int(i);
  return -1;
}

bool TemperatureCell::drive_channel(size_t i, const Quantity& q, std::string* why) {
  ModuleDef& m = cfg_.modules[size_t(channels_[i].module)];
  const size_t local = i - modules_[size_t(channels_[i].module)].first;
  if (local >= m.channels.size()) m.channels.resize(local + 1);
  ChannelDef& d = m.channels[local];
  if (q.unit == Unit::Celsius) {
    d.has_signal = false;
    d.fixed_c = q.value;
  } else {
    const bool tc = m.sensor == SensorKind::Thermocouple;
    if ((q.unit == Unit::Millivolt) != tc || q.unit == Unit::Volt || q.unit == Unit::Milliamp) {
      *why = "channel '" + channels_[i].name + "' has " + (tc ? "a thermocouple: give C or mV" : "a resistance sensor: give C or ohm");
      return false;
    }
    d.has_signal = true;
    d.signal = q;
  }
  plant_of_[i] = -1;
  return true;
}

bool TemperatureCell::drive_analog_input(const std::string& name, const Quantity& q, std::string* why) {
  if (!analog_) {
    *why = "the cell has no analog modules (modules.analog)";
    return false;
  }
  if (q.unit != Unit::Volt && q.unit != Unit::Milliamp) {
    *why = "an analog input takes V or mA";
    return false;
  }
  return analog_->drive_input(name, q.value, q.unit == Unit::Milliamp, why);
}

double TemperatureCell::true_temperature(size_t ch) const {
  const int p = plant_of_[ch];
  if (p >= 0) return plants_[size_t(p)].temperature_c();
  const ModuleDef& m = cfg_.modules[size_t(channels_[ch].module)];
  const size_t local = ch - modules_[size_t(channels_[ch].module)].first;
  return local < m.channels.size() ? m.channels[local].fixed_c : 25.0;
}

// Temperature -> the sensor's signal -> what the module computes back from it.
double TemperatureCell::sense(const ModuleDef& m, double t, bool* out_of_range) const {
  double lo, hi;
  range_of(m, &lo, &hi);
  *out_of_range = t < lo || t > hi;
  t = std::clamp(t, lo, hi);  // the converter saturates at the ends of its range
  switch (m.sensor) {
    case SensorKind::Thermocouple: {
      const double emf = tc_measured_emf_mv(m.tc, t, m.cold_junction_c);  // at the terminals
      return tc_compensated_c(m.tc, emf, m.cold_junction_c);
    }
    case SensorKind::Pt100:
    case SensorKind::Pt1000: {
      const RtdCurve k = rtd_curve(m.sensor == SensorKind::Pt100 ? 100 : 1000, m.alpha);
      return rtd_temperature(k, rtd_resistance(k, t));
    }
    case SensorKind::Ntc:
      if (m.use_sh) return ntc_temperature(m.sh, ntc_resistance(m.sh, t));
      return ntc_temperature(m.ntc, ntc_resistance(m.ntc, t));
  }
  return t;
}

// The same chain from the sensor's signal on. A thermocouple's value is its hot junction's
// emf against 0 degC (the NIST tables' number): the terminals, at the module's cold-junction
// temperature, see that minus E(cold junction), and the module adds E(cold junction) back.
double TemperatureCell::sense_signal(const ModuleDef& m, const Quantity& q, bool* out_of_range) const {
  double t = 0;
  switch (m.sensor) {
    case SensorKind::Thermocouple: {
      const double terminal_mv = q.value - tc_emf_mv(m.tc, m.cold_junction_c);
      t = tc_compensated_c(m.tc, terminal_mv, m.cold_junction_c);
      break;
    }
    case SensorKind::Pt100:
    case SensorKind::Pt1000:
      t = rtd_temperature(rtd_curve(m.sensor == SensorKind::Pt100 ? 100 : 1000, m.alpha), q.value);
      break;
    case SensorKind::Ntc:
      t = m.use_sh ? ntc_temperature(m.sh, q.value) : ntc_temperature(m.ntc, q.value);
      break;
  }
  double lo, hi;
  range_of(m, &lo, &hi);
  *out_of_range = t < lo || t > hi;
  return std::clamp(t, lo, hi);  // the converter saturates at the ends of its range
}

void TemperatureCell::sample(size_t i) {
  ChannelState& ch = channels_[i];
  ch.open = wired_open_[i];
  if (ch.open) {  // a broken line restarts the average when it is mended
    ch.window.clear();
    ch.next = 0;
    return;
  }
  const ModuleDef& m = cfg_.modules[size_t(ch.module)];
  const size_t local = i - modules_[size_t(ch.module)].first;
  const ChannelDef* def = local < m.channels.size() ? &m.channels[local] : nullptr;
  const double v = def && def->has_signal && plant_of_[i] < 0 ? sense_signal(m, def->signal, &ch.out_of_range)
                                                             : sense(m, true_temperature(i), &ch.out_of_range);
  if (ch.window.size() < size_t(cfg_.averaging)) {
    ch.window.push_back(v);
  } else {
    ch.window[ch.next] = v;
  }
  ch.next = (ch.next + 1) % size_t(cfg_.averaging);
  double sum = 0;
  for (double s : ch.window) sum += s;
  ch.value_c = sum / double(ch.window.size());
}

void TemperatureCell::after_program(uint64_t now_us) {
  if (analog_) analog_->after_program(now_us);
}

void TemperatureCell::before_inputs(uint64_t now_us) {
  if (analog_) analog_->before_inputs(now_us);
  const uint64_t dt = have_time_ && now_us > last_us_ ? now_us - last_us_ : 0;
  have_time_ = true;
  last_us_ = now_us;
  // Plants: the actuators as the previous scan left them, held over dt.
  for (size_t p = 0; p < plants_.size(); ++p) {
    const PlantDef& d = plant_defs_[p];
    auto power = [&](bool has, bool analog, const Address& a) {
      if (!has) return 0.0;
      if (!analog) return mem_.bit(a.area, a.index) ? 1.0 : 0.0;
      return double(mem_.reg(a.area, a.index)) / d.full_scale;
    };
    if (dt) plants_[p].step(dt, power(d.has_heater, d.heater_analog, d.heater),
                            power(d.has_cooler, d.cooler_analog, d.cooler));
  }
  // Modules: each converts one channel per slot, round robin (time-domain multiplexing).
  bool all = !modules_.empty();
  for (auto& m : modules_) {
    const uint64_t due = now_us / m.slot_us;  // slots that have started by now
    if (due > m.next_slot + uint64_t(m.count)) m.next_slot = due - uint64_t(m.count);  // after a long gap
    for (; m.next_slot <= due; ++m.next_slot) {
      m.current = int(m.next_slot % uint64_t(m.count));
      sample(m.first + size_t(m.current));
      ++m.reads;
    }
    all &= m.reads >= uint32_t(m.count);
  }
  all_read_ = all;
}

std::string ChannelReading::state() const {
  if (!installed) return "not installed";
  if (raw == kLineBrokenValue) return "line broken";
  if (abnormal) return "out of range";
  return std::to_string(raw / 10.0);
}

std::vector<ChannelReading> TemperatureCell::readings(const Memory& m) const {
  const uint32_t inst = m.reg(Area::R, treg::kInstalled) | uint32_t(m.reg(Area::R, treg::kInstalled + 1)) << 16;
  const uint16_t* wr = m.words(cfg_.working.area) + cfg_.working.index;
  const uint32_t abn = wr[1] | uint32_t(wr[2]) << 16;
  const bool f = cfg_.fahrenheit;
  std::vector<ChannelReading> out(channels_.size());
  for (size_t i = 0; i < out.size(); ++i) {
    ChannelReading& r = out[i];
    r.raw = int16_t(m.reg(cfg_.readings.area, cfg_.readings.index + uint32_t(i)));
    r.installed = inst >> i & 1u;
    r.abnormal = abn >> i & 1u;
    r.broken = !r.installed || r.raw == kLineBrokenValue;
    const double v = r.raw / 10.0;
    r.celsius = r.broken ? std::numeric_limits<double>::quiet_NaN() : f ? (v - 32.0) * 5.0 / 9.0 : v;
    const double q = channels_[i].resolution_c * (f ? 5.0 / 9.0 : 1.0);
    r.variance_c2 = q * q / 12.0;
  }
  return out;
}

int16_t TemperatureCell::register_value(double c, double resolution_c) const {
  double v = cfg_.fahrenheit ? c * 9.0 / 5.0 + 32.0 : c;
  const double step = resolution_c >= 1.0 ? 10.0 : 1.0;  // in 0.1 degree units
  v = std::round(v * 10.0 / step) * step;
  return static_cast<int16_t>(std::clamp(v, -32768.0, 32766.0));
}

void TemperatureCell::before_program(uint64_t now_us) {
  if (mem_.bit(Area::M, special::kFirstScan)) {
    // The manual's defaults (A:6945, A:7170-A:7177; FB: B:385-B:436, B:705-B:711); the
    // program may overwrite them.
    const bool fb = cfg_.generation == Generation::FB;
    mem_.set_reg(Area::R, treg::kIntervals, fb ? 0x0000 : 0x0102);
    mem_.set_reg(Area::R, treg::kLargePower, 90);
    mem_.set_reg(Area::R, treg::kLargePowerTime, 600);
    mem_.set_reg(Area::R, treg::kHighAlarm, fb ? 350 : 3500);
    for (uint32_t r = 0; r < 4; ++r) mem_.set_reg(Area::R, treg::kInstalled + r, 0xFFFF);
    if (fb) {  // R4014 500 ms, R4015 no averaging, R4016-R4019, R4020 DIN/R, R4021 R8000, R4022/R4023
      const uint16_t d[] = {500, 0, 248, 286, 240, 280, 0x0001, 8000, 1024, 1024};
      for (uint32_t r = 0; r < 10; ++r) mem_.set_reg(Area::R, treg::kFbSlotMs + r, d[r]);
    }
  }
  if (!modules_.empty()) write_registers();
  if (fb_) fb_->before_program();
  if (analog_) analog_->before_program(now_us);
}

void TemperatureCell::write_registers() {
  const uint32_t n = uint32_t(channels_.size());
  uint16_t abnormal[2] = {0, 0};
  uint16_t* readings = mem_.words(cfg_.readings.area) + cfg_.readings.index;
  const uint32_t installed = mem_.reg(Area::R, treg::kInstalled) | uint32_t(mem_.reg(Area::R, treg::kInstalled + 1)) << 16;
  for (uint32_t i = 0; i < n; ++i) {
    const ChannelState& ch = channels_[i];
    int16_t v = 0;
    if (installed >> i & 1u) {
      if (ch.open) {
        v = kLineBrokenValue;
      } else if (!std::isnan(ch.value_c)) {
        v = register_value(ch.value_c, ch.resolution_c);
      }
      if (ch.open || ch.out_of_range) abnormal[i / 16] |= uint16_t(1u << (i % 16));
    }
    readings[i] = static_cast<uint16_t>(v);
  }
  uint16_t* wr = mem_.words(cfg_.working.area) + cfg_.working.index;
  wr[0] = static_cast<uint16_t>((all_read_ ? kExecMeasuring : 0) << 8);
  wr[1] = abnormal[0];
  wr[2] = abnormal[1];
  wr[3] = static_cast<uint16_t>(n << 8 | modules_.size());
  uint32_t ir = cfg_.first_ir;
  for (size_t k = 0; k < modules_.size(); ++k) {
    const ModuleDef& d = cfg_.modules[k];
    const ModuleState& m = modules_[k];
    uint16_t* w = wr + 4 + 4 * k;
    w[0] = static_cast<uint16_t>(d.sensor_code() << 8 | (k & 0xFF));  // DO group: the module's index
    w[1] = static_cast<uint16_t>(m.count << 8 | (ir & 0xFF));
    w[2] = static_cast<uint16_t>(m.first);
    w[3] = static_cast<uint16_t>(m.current);
    // The module's IR shows the channel it is converting (the multiplexed input).
    if (ir < 64) mem_.set_reg(Area::R, 3840 + ir, readings[m.first + size_t(m.current)]);
    ir += uint32_t(module_info(d.kind).irs);
  }
  if (cfg_.has_table) {
    uint16_t* sr = mem_.words(cfg_.table.area) + cfg_.table.index;
    sr[0] = 0xA556;
    sr[1] = static_cast<uint16_t>(modules_.size() << 8);
    sr[2] = encode(cfg_.readings);
    sr[3] = encode(cfg_.working);
    for (size_t k = 0; k < modules_.size(); ++k)
      sr[4 + k] = static_cast<uint16_t>(cfg_.modules[k].sensor_code() << 8 | module_info(cfg_.modules[k].kind).code);
  }
}

std::unique_ptr<TemperatureCell> make_temperature_cell(const YAML::Node& document, const std::string& file,
                                                       Memory& mem) {
  if (!document.IsMap() || !document["modules"]) return nullptr;
  return std::make_unique<TemperatureCell>(parse_temperature_config(document["modules"], file), mem);
}

}  // namespace temp
}  // namespace plc_cell
