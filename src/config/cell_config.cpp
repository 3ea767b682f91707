#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/error_list.h"
#include "plc_cell/config/yaml_reader.h"

#include <cmath>
#include <map>
#include <set>

#include "plc_cell/core/error.h"
#include "plc_cell/core/file_text.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/core/unreadable.h"

namespace plc_cell {
namespace {

std::string folder_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

}  // namespace

std::vector<AreaRange> CellConfig::default_retentive() {
  return {{Area::M, 800, 1399}, {Area::S, 500, 999}, {Area::R, 0, 3839},
          {Area::D, 0, 4095},   {Area::F, 0, 8191}};
}

Address CellConfig::resolve(const std::string& name_or_address) const {
  for (const auto& s : signals)
    if (s.first == name_or_address) return s.second;
  Address a;
  std::string why;
  if (try_parse_address(name_or_address, &a, &why)) return a;
  throw Error("'" + name_or_address + "' is neither a signal of cell " + name + " nor an address (" + why + ")");
}

namespace {

void parse_plc(const YamlReader& r, const YAML::Node& plc, CellConfig& cfg, ErrorList& errors) {
  const std::string& file = r.file();
  r.only(plc, "plc", {"scan_period", "watchdog", "retentive", "timer_bases", "persist", "engine"}, &errors);
  errors.collect([&] {
    if (plc["scan_period"]) cfg.scan_period_us = r.seconds_us(plc["scan_period"], "plc.scan_period", 0.0001, 1.0);
  }, file, plc);
  errors.collect([&] {
    if (plc["watchdog"]) cfg.watchdog_us = r.seconds_us(plc["watchdog"], "plc.watchdog", 0.001, 10.0);
  }, file, plc);
  errors.collect([&] {
    if (plc["engine"] && !parse_engine_choice(r.str(plc["engine"], "plc.engine"), &cfg.engine))
      r.fail(plc["engine"], "plc.engine", "expected native, interpreter or lockstep");
  }, file, plc);
  errors.collect([&] {
    const auto ret = plc["retentive"];
    if (!ret) return;
    if (!ret.IsSequence()) r.fail(ret, "plc.retentive", "expected a list of ranges such as [M800-M1399, D0-D99]");
    cfg.retentive.clear();
    for (size_t i = 0; i < ret.size(); ++i)
      cfg.retentive.push_back(r.range(ret[i], "plc.retentive[" + std::to_string(i) + "]"));
  }, file, plc);
  errors.collect([&] {
    const auto ps = plc["persist"];
    if (!ps) return;
    // "store.bin" or {file: store.bin, interval: 0.1, sync_writes: true}
    const YAML::Node f = ps.IsMap() ? ps["file"] : ps;
    if (ps.IsMap()) r.only(ps, "plc.persist", {"file", "interval", "sync_writes"});
    if (!f) r.fail(ps, "plc.persist", "expected a file name or {file: ..., interval: ..., sync_writes: ...}");
    cfg.persist.file = r.str(f, "plc.persist.file");
    if (!cfg.persist.file.empty() && cfg.persist.file[0] != '/') cfg.persist.file = folder_of(file) + cfg.persist.file;
    if (ps.IsMap() && ps["interval"])
      cfg.persist.interval_us = r.seconds_us(ps["interval"], "plc.persist.interval", 0.001, 60.0);
    if (ps.IsMap() && ps["sync_writes"]) {
      const std::string v = r.str(ps["sync_writes"], "plc.persist.sync_writes");
      if (v != "true" && v != "false") r.fail(ps["sync_writes"], "plc.persist.sync_writes", "expected true or false");
      cfg.persist.sync_writes = v == "true";
    }
  }, file, plc);
  errors.collect([&] {
    const auto tb = plc["timer_bases"];
    if (!tb) return;
    if (!tb.IsMap()) r.fail(tb, "plc.timer_bases", "expected a mapping such as {T0-T49: 0.01}");
    for (const auto& kv : tb) {
      const std::string key = "plc.timer_bases." + kv.first.as<std::string>();
      const AreaRange rg = r.range(kv.first, key);
      if (rg.area != Area::T) r.fail(kv.first, key, "timer base ranges name timers, e.g. T0-T49");
      const double base = r.number(kv.second, key, 0.0, 10.0);
      const uint64_t us = static_cast<uint64_t>(std::llround(base * 1e6));
      if (us != 10000 && us != 100000 && us != 1000000) r.fail(kv.second, key, "a timer base is 0.01, 0.1 or 1 s");
      cfg.timer_bases.push_back({rg.first, rg.last, static_cast<uint32_t>(us)});
    }
  }, file, plc);
}

// One entry of simulation.inputs.
SimInputDef parse_sim_input(const YamlReader& r, const CellConfig& cfg, const YAML::Node& name,
                            const YAML::Node& spec) {
  SimInputDef d;
  d.name = name.as<std::string>();
  const std::string key = "simulation.inputs." + d.name;
  Address a;
  try {
    a = cfg.resolve(d.name);
  } catch (const Error& e) {
    r.fail(name, key, e.what());
  }
  if (a.area != Area::X || a.width != Width::Bit) r.fail(name, key, "only inputs X0..X255 can be simulated");
  d.x = a.index;
  r.only(spec, key, {"pulse", "steps", "follow"});
  if (spec.size() != 1) r.fail(spec, key, "give exactly one of pulse, steps, follow");
  if (const auto p = spec["pulse"]) {
    r.only(p, key + ".pulse", {"period", "width", "delay"});
    d.kind = SimInputDef::Kind::Pulse;
    if (!p["period"] || !p["width"]) r.fail(p, key + ".pulse", "needs period and width (seconds)");
    d.period_us = r.seconds_us(p["period"], key + ".pulse.period", 0.0001, 1e6);
    d.width_us = r.seconds_us(p["width"], key + ".pulse.width", 0.0, 1e6);
    if (p["delay"]) d.delay_us = r.seconds_us(p["delay"], key + ".pulse.delay", 0.0, 1e6);
    if (d.width_us > d.period_us) r.fail(p["width"], key + ".pulse.width", "longer than the period");
  } else if (const auto s = spec["steps"]) {
    d.kind = SimInputDef::Kind::Steps;
    if (!s.IsSequence()) r.fail(s, key + ".steps", "expected a list of [time, level] pairs");
    uint64_t last = 0;
    for (size_t i = 0; i < s.size(); ++i) {
      const std::string k = key + ".steps[" + std::to_string(i) + "]";
      if (!s[i].IsSequence() || s[i].size() != 2) r.fail(s[i], k, "expected [time, level]");
      const uint64_t t = r.seconds_us(s[i][0], k, 0.0, 1e6);
      if (i > 0 && t < last) r.fail(s[i][0], k, "times must not decrease");
      last = t;
      d.steps.emplace_back(t, r.number(s[i][1], k, 0, 1) != 0);
    }
  } else if (const auto f = spec["follow"]) {
    r.only(f, key + ".follow", {"source", "on_delay", "off_delay", "invert"});
    d.kind = SimInputDef::Kind::Follow;
    if (!f["source"]) r.fail(f, key + ".follow", "needs a source discrete (e.g. source: Y1)");
    try {
      d.source = cfg.resolve(r.str(f["source"], key + ".follow.source"));
    } catch (const SourceError&) {
      throw;
    } catch (const Error& e) {
      r.fail(f["source"], key + ".follow.source", e.what());
    }
    if (d.source.width != Width::Bit) r.fail(f["source"], key + ".follow.source", "must be a single discrete");
    if (f["on_delay"]) d.on_delay_us = r.seconds_us(f["on_delay"], key + ".follow.on_delay", 0.0, 1e6);
    if (f["off_delay"]) d.off_delay_us = r.seconds_us(f["off_delay"], key + ".follow.off_delay", 0.0, 1e6);
    if (f["invert"]) d.invert = r.boolean(f["invert"], key + ".follow.invert");
  }
  return d;
}

}  // namespace

CellConfig parse_cell_config(const std::string& yaml_text, const std::string& file, ErrorList* errors,
                             const std::set<std::string>& sections) {
  YamlReader r(file);
  CellConfig cfg;
  cfg.file = file;
  const YAML::Node doc = r.load(yaml_text);
  cfg.document = doc;
  if (doc.IsNull()) return cfg;
  // Not a mapping: there is no section to read on.
  if (!doc.IsMap()) r.fail(doc, "", "expected a mapping of sections (cell, plc, signals, simulation, ...)");
  // Each section, and each key or entry where they are independent, is read even when
  // an earlier one failed: every error of the file is reported in one run.
  std::set<std::string> keys = {"cell", "plc", "signals", "simulation", "registers"};
  keys.insert(sections.begin(), sections.end());
  r.only(doc, "", keys, errors);
  if (const auto cell = doc["cell"]) errors->collect([&] {
    r.only(cell, "cell", {"name", "program"});
    if (cell["name"]) cfg.name = r.str(cell["name"], "cell.name");
    if (cell["program"]) {
      cfg.program = r.str(cell["program"], "cell.program");
      if (!cfg.program.empty() && cfg.program[0] != '/') cfg.program = folder_of(file) + cfg.program;
    }
  }, file, cell);
  if (const auto plc = doc["plc"]) errors->collect([&] { parse_plc(r, plc, cfg, *errors); }, file, plc);
  if (const auto sig = doc["signals"]) errors->collect([&] { cfg.signals = r.discretes(sig, "signals"); }, file, sig);
  if (const auto regs = doc["registers"])
    errors->collect([&] { cfg.registers = parse_register_groups(regs, "registers", r); }, file, regs);
  if (const auto sim = doc["simulation"]) errors->collect([&] {
    r.only(sim, "simulation", {"inputs"}, errors);
    const auto inputs = sim["inputs"];
    if (!inputs) return;
    if (!inputs.IsMap()) r.fail(inputs, "simulation.inputs", "expected a mapping of inputs to signals");
    std::map<uint32_t, std::pair<std::string, int>> driven;  // X -> the entry driving it, its line
    for (const auto& kv : inputs)
      errors->collect([&] {
        SimInputDef d = parse_sim_input(r, cfg, kv.first, kv.second);
        const auto it = driven.find(d.x);
        if (it != driven.end())
          r.fail(kv.first, "simulation.inputs." + d.name,
                 "X" + std::to_string(d.x) + " is already driven by '" + it->second.first + "' (line " +
                     std::to_string(it->second.second) + "); an input has one signal");
        driven[d.x] = {d.name, YamlReader::line(kv.first)};
        cfg.sim_inputs.push_back(std::move(d));
      }, file, kv.first);
  }, file, sim);
  return cfg;
}

CellConfig parse_cell_config(const std::string& yaml_text, const std::string& file,
                             const std::set<std::string>& sections) {
  ErrorList errors;
  CellConfig cfg = parse_cell_config(yaml_text, file, &errors, sections);
  errors.throw_if_any();
  return cfg;
}

CellConfig load_cell_config(const std::string& path, ErrorList* errors, const std::set<std::string>& sections) {
  const std::string why = why_unreadable(path);
  if (!why.empty()) throw SourceError::at(path, 0, 0, "cannot open the cell config: " + why);
  const std::optional<std::string> text = file_text(path);
  if (!text) throw SourceError::at(path, 0, 0, "cannot open the cell config");
  return parse_cell_config(*text, path, errors, sections);
}

CellConfig load_cell_config(const std::string& path, const std::set<std::string>& sections) {
  ErrorList errors;
  CellConfig cfg = load_cell_config(path, &errors, sections);
  errors.throw_if_any();
  return cfg;
}

uint64_t parse_duration_us(const std::string& text) {
  size_t pos = 0;
  double v;
  try {
    v = std::stod(text, &pos);
  } catch (const std::exception&) {
    throw Error("bad duration '" + text + "' (examples: 2.5s, 100ms, 500us)");
  }
  const std::string unit = text.substr(pos);
  double scale;
  if (unit.empty() || unit == "s") scale = 1e6;
  else if (unit == "ms") scale = 1e3;
  else if (unit == "us") scale = 1;
  else if (unit == "min") scale = 60e6;
  else throw Error("bad duration '" + text + "': unit must be s, ms, us or min");
  if (!(v >= 0) || v * scale > 1e15) throw Error("bad duration '" + text + "': out of range");
  return static_cast<uint64_t>(std::llround(v * scale));
}

}  // namespace plc_cell
