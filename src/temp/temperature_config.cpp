#include "plc_cell/temp/temperature_config.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "plc_cell/config/error_list.h"
#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"
#include "plc_cell/temp/fb_modules.h"
#include "plc_cell/temp/rtd.h"

namespace plc_cell {
namespace temp {
namespace {

// Codes for SR+4.. are plc_cell's: the manual names the modules but gives no numbers.
const ModuleInfo kModules[] = {
    {"2TC", 2, 1, 1, 2, 1},    {"6TC", 6, 2, 2, 4, 1},    {"16TC", 16, 3, 3, 6, 1},
    {"6RTD", 6, 4, 1, 2, 1},   {"16RTD", 16, 5, 2, 4, 1}, {"6NTC", 6, 6, 1, 2, 1},
    {"2A4TC", 4, 7, 2, 4, 2},  {"2A4RTD", 4, 8, 1, 2, 2},
};

ChannelDef parse_channel(const YamlReader& r, const YAML::Node& n, const std::string& key) {
  r.only(n, key, {"name", "plant", "temperature", "value", "open"});
  ChannelDef c;
  if (n["name"]) c.name = r.topic_name(n["name"], key + ".name", "temperature channel");
  if (n["plant"]) c.plant = r.str(n["plant"], key + ".plant");
  if (n["temperature"]) c.fixed_c = r.number(n["temperature"], key + ".temperature", -273, 3000);
  if (n["open"]) c.open = r.boolean(n["open"], key + ".open");
  if (const YAML::Node v = n["value"]) {
    if (n["plant"] || n["temperature"]) r.fail(v, key + ".value", "give one of plant, temperature, value");
    const std::string text = r.str(v, key + ".value");
    c.signal = r.checked(v, key + ".value", [&] { return parse_quantity(text); });
    if (c.signal.unit == Unit::Celsius) {
      if (!(c.signal.value >= -273 && c.signal.value <= 3000))
        r.fail(v, key + ".value", "value " + v.as<std::string>() + " out of range -273..3000 C");
      c.fixed_c = c.signal.value;
    } else {
      c.has_signal = true;  // its unit is checked against the module's sensor
    }
  }
  return c;
}

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4f", v);
  return b;
}
std::string shortest(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

// A channel's `value` in the unit of the module's sensor, inside the range where the
// sensor's standard defines it (NIST ITS-90 emf for a thermocouple, IEC 60751 -200..850
// degC for an RTD); an NTC takes any resistance above 0.
void check_signal(const YamlReader& r, const YAML::Node& n, const std::string& key, const ModuleDef& m,
                  const ChannelDef& c) {
  if (!c.has_signal) return;
  const YAML::Node v = n["value"];
  const std::string k = key + ".value";
  const std::string given = v.as<std::string>();
  double lo, hi;
  switch (m.sensor) {
    case SensorKind::Thermocouple:
      if (c.signal.unit != Unit::Millivolt)
        r.fail(v, k, "a thermocouple's value is in mV (or C), got '" + given + "'");
      lo = tc_emf_mv(m.tc, tc_min_c(m.tc)), hi = tc_emf_mv(m.tc, tc_max_c(m.tc));
      if (!(c.signal.value >= lo && c.signal.value <= hi))
        r.fail(v, k, "'" + given + "' out of range " + fmt(lo) + ".." + fmt(hi) + " mV (type " + to_string(m.tc) +
                         ", NIST ITS-90 " + shortest(tc_min_c(m.tc)) + ".." + shortest(tc_max_c(m.tc)) + " C)");
      return;
    case SensorKind::Pt100:
    case SensorKind::Pt1000: {
      if (c.signal.unit != Unit::Ohm) r.fail(v, k, "an RTD's value is in ohm (or C), got '" + given + "'");
      const RtdCurve curve = rtd_curve(m.sensor == SensorKind::Pt100 ? 100 : 1000, m.alpha);
      lo = rtd_resistance(curve, -200), hi = rtd_resistance(curve, 850);
      if (!(c.signal.value >= lo && c.signal.value <= hi))
        r.fail(v, k, "'" + given + "' out of range " + fmt(lo) + ".." + fmt(hi) + " ohm (-200..850 C)");
      return;
    }
    case SensorKind::Ntc:
      if (c.signal.unit != Unit::Ohm) r.fail(v, k, "an NTC's value is in ohm (or C), got '" + given + "'");
      if (!(c.signal.value > 0)) r.fail(v, k, "'" + given + "' out of range: a resistance above 0 ohm");
      return;
  }
}

ModuleDef parse_module(const YamlReader& r, const YAML::Node& n, const std::string& key) {
  r.only(n, key, {"type", "sensor", "alpha", "cold_junction", "r25", "beta", "steinhart_hart", "channels"});
  ModuleDef m;
  if (!n["type"]) r.fail(n, key + ".type", "missing");
  const std::string type = r.str(n["type"], key + ".type");
  bool found = false;
  for (int k = 0; k < 8; ++k)
    if (type == kModules[k].name) m.kind = static_cast<ModuleKind>(k), found = true;
  if (!found) r.fail(n["type"], key + ".type", "unknown module '" + type + "' (2TC, 6TC, 16TC, 6RTD, 16RTD, 6NTC, 2A4TC, 2A4RTD)");
  const bool tc = m.kind == ModuleKind::TC2 || m.kind == ModuleKind::TC6 || m.kind == ModuleKind::TC16 ||
                  m.kind == ModuleKind::A4TC2;
  const bool ntc = m.kind == ModuleKind::NTC6;
  const std::string sensor = n["sensor"] ? r.str(n["sensor"], key + ".sensor") : (tc ? "K" : ntc ? "NTC" : "PT100");
  if (tc) {
    m.sensor = SensorKind::Thermocouple;
    m.tc = r.checked(n["sensor"], key + ".sensor", [&] { return tc_type_from_string(sensor); });
  } else if (ntc) {
    if (sensor != "NTC") r.fail(n["sensor"], key + ".sensor", "a 6NTC takes NTC sensors");
    m.sensor = SensorKind::Ntc;
  } else if (sensor == "PT100" || sensor == "PT1000") {
    m.sensor = sensor == "PT100" ? SensorKind::Pt100 : SensorKind::Pt1000;
  } else {
    r.fail(n["sensor"], key + ".sensor", "an RTD module takes PT100 or PT1000");
  }
  if (n["alpha"]) {
    m.alpha = r.str(n["alpha"], key + ".alpha");
    if (m.alpha != "DIN" && m.alpha != "JIS") r.fail(n["alpha"], key + ".alpha", "DIN or JIS");
  }
  if (n["cold_junction"]) m.cold_junction_c = r.number(n["cold_junction"], key + ".cold_junction", -20, 80);
  if (n["r25"]) {
    m.ntc.r25 = r.number(n["r25"], key + ".r25", 2000, 20000);
    const double r25 = m.ntc.r25;
    if (r25 != 2000 && r25 != 5000 && r25 != 10000 && r25 != 20000)
      r.fail(n["r25"], key + ".r25", "the FBs-6NTC takes 2k, 5k, 10k or 20k at 25 degC");
  }
  if (n["beta"]) m.ntc.beta = r.number(n["beta"], key + ".beta", 1000, 10000);
  if (const YAML::Node sh = n["steinhart_hart"]) {
    if (!ntc) r.fail(sh, key + ".steinhart_hart", "only for a 6NTC");
    if (!sh.IsSequence() || sh.size() != 3) r.fail(sh, key + ".steinhart_hart", "expected [a, b, c]");
    m.sh = {r.number(sh[0], key + ".steinhart_hart", -1, 1), r.number(sh[1], key + ".steinhart_hart", -1, 1),
            r.number(sh[2], key + ".steinhart_hart", -1, 1)};
    m.use_sh = true;
  }
  if (n["channels"]) {
    const YAML::Node& ch = n["channels"];
    if (!ch.IsSequence()) r.fail(ch, key + ".channels", "expected a list");
    if (int(ch.size()) > module_info(m.kind).channels)
      r.fail(ch, key + ".channels", "a " + type + " has " + std::to_string(module_info(m.kind).channels) + " channels");
    for (size_t i = 0; i < ch.size(); ++i) {
      const std::string ck = key + ".channels[" + std::to_string(i) + "]";
      m.channels.push_back(parse_channel(r, ch[i], ck));
      check_signal(r, ch[i], ck, m, m.channels.back());
    }
  }
  return m;
}

PlantDef parse_plant(const YamlReader& r, const YAML::Node& n, const std::string& key) {
  r.only(n, key, {"name", "ambient", "initial", "gain", "cooling_gain", "time_constant", "dead_time", "heater",
                  "cooler", "full_scale"});
  PlantDef p;
  if (!n["name"]) r.fail(n, key + ".name", "missing");
  p.name = r.str(n["name"], key + ".name");
  auto& q = p.params;
  if (n["ambient"]) q.ambient_c = r.number(n["ambient"], key + ".ambient", -200, 1500);
  q.initial_c = q.ambient_c;
  if (n["initial"]) q.initial_c = r.number(n["initial"], key + ".initial", -273, 3000);
  if (n["gain"]) q.gain_c = r.number(n["gain"], key + ".gain", 0, 3000);
  if (n["cooling_gain"]) q.cooling_gain_c = r.number(n["cooling_gain"], key + ".cooling_gain", 0, 3000);
  if (n["time_constant"]) q.tau_s = r.number(n["time_constant"], key + ".time_constant", 0.1, 1e6);
  if (n["dead_time"]) q.dead_time_s = r.number(n["dead_time"], key + ".dead_time", 0, 3600);
  if (n["full_scale"]) p.full_scale = r.number(n["full_scale"], key + ".full_scale", 1, 65535);
  auto actuator = [&](const char* k, bool* has, bool* analog, Address* a) {
    if (!n[k]) return;
    *a = r.address(n[k], key + "." + k);
    *has = true;
    *analog = a->width != Width::Bit;
    if (*analog && a->width != Width::Word) r.fail(n[k], key + "." + k, "a bit or a 16-bit register");
  };
  actuator("heater", &p.has_heater, &p.heater_analog, &p.heater);
  actuator("cooler", &p.has_cooler, &p.cooler_analog, &p.cooler);
  return p;
}

}  // namespace

const ModuleInfo& module_info(ModuleKind k) { return kModules[static_cast<int>(k)]; }

ChannelDef parse_channel_def(const YAML::Node& n, const std::string& key, const std::string& file) {
  return parse_channel(YamlReader(file), n, key);
}

Generation cell_generation(const YAML::Node& document, const std::string& file) {
  if (!document.IsMap() || !document["modules"] || !document["modules"].IsMap()) return Generation::FBs;
  const YAML::Node g = document["modules"]["generation"];
  if (!g) return Generation::FBs;
  const YamlReader r(file);
  const std::string v = r.str(g, "modules.generation");
  if (v != "FBs" && v != "FB") r.fail(g, "modules.generation", "FBs or FB (the older FB series)");
  return v == "FB" ? Generation::FB : Generation::FBs;
}

int ModuleDef::sensor_code() const {
  switch (sensor) {
    case SensorKind::Thermocouple: return static_cast<int>(tc);  // J K E T R S B N = 0..7
    case SensorKind::Pt100: return alpha == "JIS" ? 0x12 : 0x10;
    case SensorKind::Pt1000: return alpha == "JIS" ? 0x13 : 0x11;
    case SensorKind::Ntc: return 0x20;
  }
  return 0;
}

int TemperatureConfig::total_channels() const {
  int n = 0;
  for (const auto& m : modules) n += module_info(m.kind).channels;
  return n;
}

namespace {

void parse_loops(const YamlReader& r, const YAML::Node& ls, const std::string& k, TemperatureConfig& c) {
  if (!ls.IsSequence()) r.fail(ls, k + ".loops", "expected a list");
  for (size_t i = 0; i < ls.size(); ++i) {
    const std::string lk = k + ".loops[" + std::to_string(i) + "]";
    r.only(ls[i], lk, {"name", "sv", "kc", "ki", "td"});
    LoopDef l;
    if (!ls[i]["name"] || !ls[i]["sv"]) r.fail(ls[i], lk, "a loop needs name and sv");
    l.name = r.str(ls[i]["name"], lk + ".name");
    l.sv = r.data_register(ls[i]["sv"], lk + ".sv");
    if (ls[i]["kc"]) l.kc = r.data_register(ls[i]["kc"], lk + ".kc"), l.has_kc = true;
    if (ls[i]["ki"]) l.ki = r.data_register(ls[i]["ki"], lk + ".ki"), l.has_ki = true;
    if (ls[i]["td"]) l.td = r.data_register(ls[i]["td"], lk + ".td"), l.has_td = true;
    c.loops.push_back(l);
  }
}

// modules.temperature; each module entry is read even after an error in another.
void parse_temperature(const YamlReader& r, const YAML::Node& t, const std::string& file, ErrorList& errors,
                       TemperatureConfig& c) {
  const std::string k = "modules.temperature";
  r.only(t, k, {"scan", "unit", "averaging", "readings", "working", "table", "first_ir", "modules", "loops"});
  if (const YAML::Node ls = t["loops"]) parse_loops(r, ls, k, c);
  if (t["scan"]) {
    const std::string s = r.str(t["scan"], k + ".scan");
    if (s != "normal" && s != "fast") r.fail(t["scan"], k + ".scan", "normal or fast");
    c.fast = s == "fast";
  }
  if (t["unit"]) {
    const std::string u = r.str(t["unit"], k + ".unit");
    if (u != "C" && u != "F") r.fail(t["unit"], k + ".unit", "C or F");
    c.fahrenheit = u == "F";
  }
  if (t["readings"]) c.readings = r.data_register(t["readings"], k + ".readings");
  if (t["working"]) c.working = r.data_register(t["working"], k + ".working");
  if (t["table"]) c.table = r.data_register(t["table"], k + ".table"), c.has_table = true;
  if (t["first_ir"]) c.first_ir = static_cast<uint32_t>(r.number(t["first_ir"], k + ".first_ir", 0, 63));
  if (t["modules"]) {
    const YAML::Node& ms = t["modules"];
    if (!ms.IsSequence() || ms.size() == 0 || ms.size() > 8) r.fail(ms, k + ".modules", "a list of 1 to 8 modules");
    for (size_t i = 0; i < ms.size(); ++i)
      errors.collect([&] { c.modules.push_back(parse_module(r, ms[i], k + ".modules[" + std::to_string(i) + "]")); },
                     file, ms[i]);
  }
  if (c.total_channels() > 32)
    r.fail(t["modules"], k + ".modules", "more than 32 temperature points (the FBs limit)");
  if (t["averaging"]) {
    const int a = static_cast<int>(r.number(t["averaging"], k + ".averaging", 1, 16));
    bool ntc_only = true;
    for (const auto& m : c.modules) ntc_only &= m.kind == ModuleKind::NTC6;
    if (a != 1 && a != 2 && a != 4 && a != 8 && !(a == 16 && ntc_only))
      r.fail(t["averaging"], k + ".averaging", "1, 2, 4 or 8 (16 with NTC modules only)");
    c.averaging = a;
  }
  // Everything must fit in its area.
  r.checked(t, k, [&] {
    check_span(c.readings, std::max(1, c.total_channels()));
    check_span(c.working, 4 + 4 * uint32_t(c.modules.size()));
    if (c.has_table) check_span(c.table, 4 + uint32_t(c.modules.size()));
  });
}

bool has_plant(const TemperatureConfig& c, const std::string& name) {
  return std::any_of(c.plants.begin(), c.plants.end(), [&](const PlantDef& p) { return p.name == name; });
}

// Every plant an analog input, an FB channel or a temperature channel names exists.
void check_plant_names(const YamlReader& r, const YAML::Node& node, const TemperatureConfig& c) {
  std::vector<const std::vector<AnalogInputDef>*> analog_inputs{&c.analog.board.inputs};
  for (const auto& m : c.analog.modules) analog_inputs.push_back(&m.inputs);
  for (const auto* ins : analog_inputs)
    for (const auto& in : *ins)
      if (!in.plant.empty() && !has_plant(c, in.plant))
        r.fail(node["analog"], "modules.analog", "input '" + in.name + "' names an unknown plant '" + in.plant + "'");
  if (c.fb)
    for (const auto& m : c.fb->modules)
      for (const auto& ch : m.channels)
        if (!ch.plant.empty() && !has_plant(c, ch.plant))
          r.fail(node["fb_temperature"], "modules.fb_temperature", "channel '" + ch.name + "' names an unknown plant '" + ch.plant + "'");
}

void check_temperature_plants(const YamlReader& r, const YAML::Node& node, const TemperatureConfig& c) {
  for (const auto& m : c.modules)
    for (const auto& ch : m.channels)
      if (!ch.plant.empty() && !has_plant(c, ch.plant))
        r.fail(node["temperature"], "modules.temperature", "channel '" + ch.name + "' names an unknown plant '" + ch.plant + "'");
}

// A 2A4TC/2A4RTD in modules.analog is the AI half of one in modules.temperature.
void check_combo_modules(const YamlReader& r, const YAML::Node& node, const TemperatureConfig& c) {
  for (const char* combo : {"2A4TC", "2A4RTD"}) {
    const auto ai = std::count_if(c.analog.modules.begin(), c.analog.modules.end(),
                                  [&](const AnalogModuleDef& m) { return m.type == combo; });
    const auto tm = std::count_if(c.modules.begin(), c.modules.end(), [&](const ModuleDef& m) {
      return std::string(module_info(m.kind).name) == combo;
    });
    if (ai > tm)
      r.fail(node["analog"], "modules.analog",
             std::to_string(ai) + " " + combo + " analog part(s) but " + std::to_string(tm) + " " + combo +
                 " in modules.temperature (the AI part belongs to a temperature module)");
  }
}

}  // namespace

TemperatureConfig parse_temperature_config(const YAML::Node& node, const std::string& file) {
  const YamlReader r(file);
  TemperatureConfig c;
  if (!node) return c;
  r.only(node, "modules", {"generation", "temperature", "fb_temperature", "plants", "analog", "rtc", "pwmda"});  // rtc.cpp, pwmda.cpp
  YAML::Node doc;
  doc["modules"] = node;
  c.generation = cell_generation(doc, file);
  // R4003-R4008 and FUN86 mean different things in the two generations (spec 16.1).
  if (c.generation == Generation::FB && node["temperature"])
    r.fail(node["temperature"], "modules.temperature",
           "the FBs temperature modules belong to the FBs generation; this cell has modules.generation: FB "
           "(use modules.fb_temperature)");
  if (const YAML::Node fb = node["fb_temperature"]) {
    if (c.generation != Generation::FB)
      r.fail(fb, "modules.fb_temperature", "the FB-series modules need modules.generation: FB");
    c.fb = std::make_shared<FbConfig>(parse_fb_config(fb, file));
  }
  if (node["analog"]) c.analog = parse_analog_config(node["analog"], file), c.has_analog = true;
  // modules.temperature and modules.plants, and every module and plant entry in them, are
  // read even after an error in another, so each is reported in the same run.
  ErrorList errors;
  if (const YAML::Node t = node["temperature"]) errors.collect([&] { parse_temperature(r, t, file, errors, c); }, file, t);
  if (const YAML::Node ps = node["plants"]) errors.collect([&] {
    if (!ps.IsSequence()) r.fail(ps, "modules.plants", "expected a list");
    for (size_t i = 0; i < ps.size(); ++i)
      errors.collect([&] { c.plants.push_back(parse_plant(r, ps[i], "modules.plants[" + std::to_string(i) + "]")); },
                     file, ps[i]);
  }, file, ps);
  errors.throw_if_any();  // the checks across sections below need them whole
  check_plant_names(r, node, c);
  check_combo_modules(r, node, c);
  check_temperature_plants(r, node, c);
  return c;
}

}  // namespace temp
}  // namespace plc_cell
