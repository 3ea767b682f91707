#include "plc_cell/scenario/scenario_file.h"

#include <cstdlib>
#include <map>
#include <set>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/error_list.h"
#include "plc_cell/config/probe_facet.h"
#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/file_text.h"
#include "plc_cell/core/unreadable.h"
#include "sections.h"

namespace plc_cell {
namespace scenario {

namespace {

const std::set<std::string> kActions = {"set", "write", "force", "release", "simulate", "pulse",
                                        "ramp", "expect", "wait_until", "expect_sequence"};
const std::set<std::string> kStepKeys = {"set", "write", "force", "release", "simulate", "pulse", "ramp", "expect",
                                         "wait_until", "expect_sequence", "at", "after", "timeout",
                                         "stays", "within", "between", "tolerance"};

std::string folder_of(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

// Reads one file's steps; a case's parameters are substituted in every scalar it reads
// (${name}), so an error still points at the line that holds the placeholder.
class Reader {
 public:
  Reader(const YamlReader& r, ErrorList& errors, Naming naming) : r_(r), errors_(errors), naming_(naming) {}

  void set_parameters(const std::map<std::string, std::string>* p) { params_ = p; }

  std::string text(const YAML::Node& n, const std::string& key) const {
    if (!n.IsScalar()) r_.fail(n, key, "expected a value, not a " + std::string(n.IsMap() ? "mapping" : "list"));
    std::string s = n.Scalar(), out;
    for (size_t i = 0; i < s.size();) {
      if (s.compare(i, 2, "${") != 0) {
        out += s[i++];
        continue;
      }
      const auto end = s.find('}', i);
      if (end == std::string::npos) r_.fail(n, key, "'${' without its '}'");
      const std::string name = s.substr(i + 2, end - i - 2);
      const auto it = params_ ? params_->find(name) : std::map<std::string, std::string>::const_iterator();
      if (!params_ || it == params_->end())
        r_.fail(n, key, "${" + name + "}: no parameter '" + name + "' in this case");
      out += it->second;
      i = end + 1;
    }
    return out;
  }

  uint64_t duration(const YAML::Node& n, const std::string& key) const {
    const std::string s = text(n, key);
    return r_.checked(n, key, [&] { return parse_duration_us(s); });
  }

  Condition condition(const YAML::Node& n, const std::string& key) const {
    const std::string s = text(n, key);
    return r_.checked(n, key, [&] { return parse_condition(s, naming_); });
  }

  Probe probe(const YAML::Node& n, const std::string& key) const {
    const std::string s = text(n, key);
    return r_.checked(n, key, [&] { return parse_probe(s, naming_); });
  }

  // What a step may drive: an address or signal, or a probe whose family takes stimuli (an
  // analog input, a temperature channel: config/probe_facet.h).
  Probe drivable(const YAML::Node& n, const std::string& key) const {
    Probe p = probe(n, key);
    if (p.kind != Probe::Kind::Address && stimuli(p).stimuli.empty())
      r_.fail(n, key, p.text + " cannot be driven: write the registers behind it (an address or signal)");
    return p;
  }

  // The family of p as its extension declared it (no stimuli when none did).
  static ProbeFamily stimuli(const Probe& p) {
    return registered_probe_family(p.family).value_or(ProbeFamily{p.family, "", {}, {}});
  }

  Value value(const Probe& p, const YAML::Node& n, const std::string& key) const {
    Value v;
    v.text = text(n, key);
    if (p.kind == Probe::Kind::Address) {
      const Condition c = r_.checked(n, key, [&] { return parse_condition("X0 == " + v.text); });
      v.number = c.all[0].value;
      return v;
    }
    const ProbeInput in = r_.checked(n, key, [&] { return parse_stimulus(stimuli(p), v.text); });
    v.has_unit = true;
    v.number = in.value;
    v.unit = in.unit;
    return v;
  }

  // {probe: value, ...} in file order.
  std::vector<Assignment> assignments(const YAML::Node& map, const std::string& key, bool force) const {
    if (!map.IsMap() || map.size() == 0)
      r_.fail(map, key, "expected a mapping of addresses, signals or channels to values ({X0: on})");
    std::vector<Assignment> out;
    for (const auto& kv : map) {
      const std::string k = key + "." + kv.first.Scalar();
      Assignment a;
      a.line = YamlReader::line(kv.first);
      a.target = force ? probe(kv.first, k) : drivable(kv.first, k);
      if (force && a.target.kind != Probe::Kind::Address) r_.fail(kv.first, k, "only an address or signal can be forced");
      a.value = value(a.target, kv.second, k);
      if (force && a.value.number != 0 && a.value.number != 1) r_.fail(kv.second, k, "force takes on or off");
      out.push_back(a);
    }
    return out;
  }

  // {INPUT: WIDTH, ...}: each bit on for its width.
  void read_pulses(const YAML::Node& a, const std::string& k, Step* s) const {
    if (!a.IsMap() || a.size() == 0) r_.fail(a, k, "expected {INPUT: WIDTH}, e.g. {start_button: 100ms}");
    for (const auto& kv : a) {
      Assignment as;
      as.line = YamlReader::line(kv.first);
      as.target = probe(kv.first, k + "." + kv.first.Scalar());
      if (as.target.kind != Probe::Kind::Address) r_.fail(kv.first, k, "a pulse drives a bit (an input or a relay)");
      as.value.number = 1;
      as.value.text = "on";
      as.duration_us = duration(kv.second, k + "." + kv.first.Scalar());
      if (as.duration_us == 0) r_.fail(kv.second, k, "a pulse of 0 s is no pulse");
      s->assignments.push_back(as);
    }
  }

  // {TARGET: {from: V, to: V, over: DURATION}, ...}
  void read_ramps(const YAML::Node& a, const std::string& k, Step* s) const {
    if (!a.IsMap() || a.size() == 0)
      r_.fail(a, k, "expected {TARGET: {from: V, to: V, over: DURATION}}");
    for (const auto& kv : a) {
      const std::string kk = k + "." + kv.first.Scalar();
      Assignment as;
      as.line = YamlReader::line(kv.first);
      as.target = drivable(kv.first, kk);
      if (!kv.second.IsMap()) r_.fail(kv.second, kk, "expected {from: V, to: V, over: DURATION}");
      r_.only(kv.second, kk, {"from", "to", "over"});
      for (const char* req : {"from", "to", "over"})
        if (!kv.second[req]) r_.fail(kv.second, kk, std::string("missing '") + req + "'");
      as.from = value(as.target, kv.second["from"], kk + ".from");
      as.value = value(as.target, kv.second["to"], kk + ".to");
      if (as.from.has_unit && as.from.unit != as.value.unit)
        r_.fail(kv.second["to"], kk + ".to", "from and to must have the same unit");
      as.duration_us = duration(kv.second["over"], kk + ".over");
      s->assignments.push_back(as);
    }
  }

  // The condition and the timing keys beside it in the step (stays, within, between, timeout).
  void read_expect(const YAML::Node& n, const YAML::Node& a, const std::string& key, const std::string& k,
                   Step* s) const {
    s->cond = condition(a, k);
    if (n["tolerance"]) {
      apply_tolerance(s->cond, tolerance(n["tolerance"], key + ".tolerance"));
    }
    if (n["stays"] && (n["within"] || n["between"]))
      r_.fail(n["stays"], key + ".stays", "'stays' excludes 'within' and 'between'");
    if (n["within"] && n["between"]) r_.fail(n["within"], key + ".within", "'within' excludes 'between'");
    if (n["stays"]) s->stays_us = duration(n["stays"], key + ".stays");
    if (n["within"]) {
      s->has_window = true;
      s->window_max_us = duration(n["within"], key + ".within");
    }
    if (n["between"]) window(n["between"], key + ".between", &s->window_min_us, &s->window_max_us), s->has_window = true;
    s->timeout_us = n["timeout"] ? duration(n["timeout"], key + ".timeout") : kDefaultTimeoutUs;
  }

  // Conditions that must come true in list order, each with its own optional window.
  void read_sequence(const YAML::Node& n, const YAML::Node& a, const std::string& key, const std::string& k,
                     Step* s) const {
    if (!a.IsSequence() || a.size() == 0) r_.fail(a, k, "expected a list of conditions, in the order they must happen");
    for (size_t i = 0; i < a.size(); ++i) {
      const YAML::Node e = a[i];
      const std::string ek = k + "[" + std::to_string(i) + "]";
      SequenceEntry se;
      se.line = YamlReader::line(e);
      if (e.IsMap()) {
        r_.only(e, ek, {"that", "within", "between", "tolerance"});
        if (!e["that"]) r_.fail(e, ek, "missing 'that' (the condition)");
        se.cond = condition(e["that"], ek + ".that");
        if (e["within"] && e["between"]) r_.fail(e["within"], ek, "'within' excludes 'between'");
        if (e["within"]) se.max_us = duration(e["within"], ek + ".within");
        if (e["between"]) window(e["between"], ek + ".between", &se.min_us, &se.max_us);
        if (e["tolerance"]) apply_tolerance(se.cond, tolerance(e["tolerance"], ek + ".tolerance"));
      } else {
        se.cond = condition(e, ek);
      }
      s->sequence.push_back(se);
    }
    s->timeout_us = n["timeout"] ? duration(n["timeout"], key + ".timeout") : kDefaultTimeoutUs;
  }

  Step step(const YAML::Node& n, const std::string& key) const {
    Step s;
    s.file = r_.file();
    s.line = YamlReader::line(n);
    if (!n.IsMap()) r_.fail(n, key, "a step is a mapping (- set: {X0: on}, - after: 1s, - expect: Y0 ...)");
    r_.only(n, key, kStepKeys);
    std::string action;
    for (const auto& kv : n)
      if (kActions.count(kv.first.Scalar())) {
        if (!action.empty())
          r_.fail(kv.first, key, "one action per step: '" + action + "' and '" + kv.first.Scalar() + "'");
        action = kv.first.Scalar();
      }
    if (n["at"] && n["after"]) r_.fail(n["after"], key + ".after", "'at' and 'after' exclude each other");
    if (n["at"]) {
      s.has_at = true;
      s.at_us = duration(n["at"], key + ".at");
    }
    if (n["after"]) s.after_us = duration(n["after"], key + ".after");
    if (action.empty() && !n["at"] && !n["after"])
      r_.fail(n, key, "a step needs an action (set, write, force, release, simulate, pulse, ramp, expect, wait_until, "
                      "expect_sequence) or a time (at, after)");
    s.key = action.empty() ? (n["at"] ? "at" : "after") : action;
    auto only_for = [&](const char* k, std::initializer_list<const char*> actions) {
      if (!n[k]) return;
      for (const char* a : actions)
        if (action == a) return;
      std::string list;
      for (const char* a : actions) list += (list.empty() ? "" : " or ") + std::string(a);
      r_.fail(n[k], key + "." + k, std::string("'") + k + "' goes with " + list);
    };
    only_for("timeout", {"wait_until", "expect_sequence"});
    only_for("stays", {"expect"});
    only_for("within", {"expect"});
    only_for("between", {"expect"});
    only_for("tolerance", {"expect", "wait_until"});
    const std::string k = key + "." + action;
    const YAML::Node a = action.empty() ? YAML::Node() : n[action];
    if (action.empty()) {
      s.kind = Step::Kind::Wait;
    } else if (action == "set" || action == "write" || action == "force") {
      s.kind = action == "set" ? Step::Kind::Set : action == "write" ? Step::Kind::Write : Step::Kind::Force;
      s.assignments = assignments(a, k, action == "force");
      if (action == "write")
        for (const auto& as : s.assignments)
          if (as.target.kind != Probe::Kind::Address)
            r_.fail(a, k, as.target.text + ": write takes addresses and signals (set drives channels)");
    } else if (action == "release" || action == "simulate") {
      // A list of points, one point, or "all" (no assignment).
      s.kind = action == "release" ? Step::Kind::Release : Step::Kind::Simulate;
      std::vector<YAML::Node> items;
      if (a.IsSequence()) {
        for (const auto& i : a) items.push_back(i);
      } else if (!(a.IsScalar() && text(a, k) == "all")) {
        items.push_back(a);
      }
      for (const auto& i : items) {
        Assignment as;
        as.line = YamlReader::line(i);
        as.target = probe(i, k);
        if (as.target.kind != Probe::Kind::Address)
          r_.fail(i, k, action == "release" ? "only an address or signal is forced" : "only an input (X) is simulated");
        s.assignments.push_back(as);
      }
    } else if (action == "pulse") {
      s.kind = Step::Kind::Pulse;
      read_pulses(a, k, &s);
    } else if (action == "ramp") {
      s.kind = Step::Kind::Ramp;
      read_ramps(a, k, &s);
    } else if (action == "expect" || action == "wait_until") {
      s.kind = action == "expect" ? Step::Kind::Expect : Step::Kind::WaitUntil;
      read_expect(n, a, key, k, &s);
    } else {
      s.kind = Step::Kind::Sequence;
      read_sequence(n, a, key, k, &s);
    }
    return s;
  }

  // Every step of a list, each error reported and the rest read on.
  void steps(const YAML::Node& list, const std::string& key, std::vector<Step>* out) const {
    if (!list) return;
    if (!list.IsSequence()) {
      errors_.add(ErrorList::diagnostic(r_.file(), list, "key '" + key + "': expected a list of steps"));
      return;
    }
    for (size_t i = 0; i < list.size(); ++i) {
      const YAML::Node n = list[i];
      errors_.collect([&] { out->push_back(step(n, key + "[" + std::to_string(i) + "]")); }, r_.file(), n);
    }
  }

 private:
  double tolerance(const YAML::Node& n, const std::string& key) const {
    const std::string t = text(n, key);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0' || !(v >= 0)) r_.fail(n, key, "a tolerance is a number >= 0, not '" + t + "'");
    return v;
  }

  void window(const YAML::Node& n, const std::string& key, uint64_t* lo, uint64_t* hi) const {
    if (!n.IsSequence() || n.size() != 2) r_.fail(n, key, "expected [EARLIEST, LATEST], e.g. [1.4s, 1.6s]");
    *lo = duration(n[0], key + "[0]");
    *hi = duration(n[1], key + "[1]");
    if (*lo > *hi) r_.fail(n, key, "the earliest time is after the latest");
  }

  const YamlReader& r_;
  ErrorList& errors_;
  const Naming naming_;
  const std::map<std::string, std::string>* params_ = nullptr;
};

// The files the scenario names, resolved against its folder: the cell and its program, or
// the line (docs/lines.md), whose file names each cell's.
void read_files(const YamlReader& r, const YAML::Node& doc, Scenario& sc, ErrorList& errors) {
  const std::string& file = sc.file;
  auto path = [&](const char* key, std::string* out, SourceLocation* at) {
    const std::string p = r.str(doc[key], key);
    *out = !p.empty() && p[0] == '/' ? p : folder_of(file) + p;
    *at = {file, YamlReader::line(doc[key]), doc[key].Mark().column + 1};
  };
  if (doc["line"]) {
    errors.collect([&] {
      if (doc["cell"]) r.fail(doc["cell"], "cell", "a scenario runs a cell or a line, not both: 'line' is given");
      if (doc["program"])
        r.fail(doc["program"], "program", "a line's programs are named in its line file, one per cell");
      path("line", &sc.line, &sc.line_at);
    }, file, doc);
    return;
  }
  errors.collect([&] {
    if (!doc["cell"]) r.fail(doc, "cell", "missing 'cell' (or 'line'): the cell YAML this scenario runs");
    path("cell", &sc.cell, &sc.cell_at);
  }, file, doc);
  errors.collect([&] {
    if (doc["program"]) path("program", &sc.program, &sc.program_at);
  }, file, doc);
}

// A case's rows of parameters, each a case of its own: the rows and their cases' names.
// One row of none when the case has no parameters; false on an error.
bool read_rows(const YamlReader& r, const YAML::Node& c, const std::string& key, const std::string& name,
               std::vector<std::map<std::string, std::string>>* rows, std::vector<std::string>* row_names,
               ErrorList& errors) {
  if (!c["parameters"]) {
    rows->emplace_back();
    row_names->push_back(name);
    return true;
  }
  const YAML::Node ps = c["parameters"];
  return errors.collect([&] {
    if (!ps.IsSequence() || ps.size() == 0)
      r.fail(ps, key + ".parameters", "expected a list of rows, each a mapping ({n: 3, parts: 3})");
    std::set<std::string> columns;
    for (size_t j = 0; j < ps.size(); ++j) {
      const std::string rk = key + ".parameters[" + std::to_string(j) + "]";
      if (!ps[j].IsMap()) r.fail(ps[j], rk, "a row is a mapping of names to values");
      std::map<std::string, std::string> row;
      std::string rn;
      for (const auto& kv : ps[j]) {
        const std::string col = kv.first.Scalar();
        if (!kv.second.IsScalar()) r.fail(kv.second, rk + "." + col, "a parameter is a single value");
        row[col] = kv.second.Scalar();
        rn += (rn.empty() ? "" : ",") + col + "=" + kv.second.Scalar();
      }
      std::set<std::string> cols;
      for (const auto& kv : row) cols.insert(kv.first);
      if (j == 0) columns = cols;
      else if (cols != columns) r.fail(ps[j], rk, "every row needs the same names as the first");
      rows->push_back(row);
      row_names->push_back(name + "[" + rn + "]");
    }
  }, r.file(), ps);
}

// One case of the file, as one Case per row of its parameters.
void read_case(const YamlReader& r, Reader& rd, const YAML::Node& c, const std::string& key,
               const std::vector<Step>& common, std::set<std::string>& names, Scenario& sc, ErrorList& errors) {
  const std::string& file = sc.file;
  if (!c.IsMap()) {
    errors.add(ErrorList::diagnostic(file, c, "key '" + key + "': a case is a mapping with name and steps"));
    return;
  }
  r.only(c, key, {"name", "setup", "steps", "parameters"}, &errors);
  std::string name;
  if (!errors.collect([&] {
        if (!c["name"]) r.fail(c, key, "missing 'name'");
        name = r.str(c["name"], key + ".name");
        if (!c["steps"]) r.fail(c, key, "missing 'steps'");
      }, file, c))
    return;
  std::vector<std::map<std::string, std::string>> rows;
  std::vector<std::string> row_names;
  if (!read_rows(r, c, key, name, &rows, &row_names, errors)) return;
  for (size_t j = 0; j < rows.size(); ++j) {
    Case cs;
    cs.name = row_names[j];
    cs.file = file;
    cs.line = YamlReader::line(c);
    if (!names.insert(cs.name).second) {
      errors.add(ErrorList::diagnostic(file, c["name"], "key '" + key + ".name': a second case named '" + cs.name + "'"));
      continue;
    }
    rd.set_parameters(c["parameters"] ? &rows[j] : nullptr);
    cs.steps = common;
    rd.steps(c["setup"], key + ".setup", &cs.steps);
    rd.steps(c["steps"], key + ".steps", &cs.steps);
    sc.cases.push_back(std::move(cs));
  }
}

}  // namespace

Scenario parse_scenario(const std::string& text, const std::string& file, ErrorList& errors) {
  const YamlReader r(file);
  Scenario sc;
  sc.file = file;
  YAML::Node doc;
  if (!errors.collect([&] { doc = r.load(text); }, file)) return sc;
  if (!doc.IsMap()) {
    errors.add(SourceError::at(file, 1, 1, "a scenario file is a mapping with 'cell' and 'cases'"));
    return sc;
  }
  r.only(doc, "", {"cell", "line", "program", "setup", "cases", "properties", "explore", "hardware"}, &errors);
  read_files(r, doc, sc, errors);
  const Naming naming = doc["line"] ? Naming::Line : Naming::Cell;
  sc.properties = read_properties(r, doc["properties"], errors, naming);
  sc.explore = read_explore(r, doc["explore"], errors, naming);
  sc.hardware = read_hardware(r, doc["hardware"], errors);
  Reader rd(r, errors, naming);
  std::vector<Step> common;
  rd.steps(doc["setup"], "setup", &common);
  const YAML::Node cases = doc["cases"];
  if (!cases && doc["explore"]) return sc;  // a file for plc_cell explore alone
  if (!cases || !cases.IsSequence() || cases.size() == 0) {
    errors.add(ErrorList::diagnostic(file, cases ? cases : doc, "key 'cases': expected a list of test cases"));
    return sc;
  }
  std::set<std::string> names;
  for (size_t i = 0; i < cases.size(); ++i)
    read_case(r, rd, cases[i], "cases[" + std::to_string(i) + "]", common, names, sc, errors);
  for (auto& c : sc.cases) c.properties = sc.properties;
  return sc;
}

Scenario parse_scenario(const std::string& text, const std::string& file) {
  ErrorList errors;
  Scenario sc = parse_scenario(text, file, errors);
  errors.throw_if_any();
  return sc;
}

Scenario read_scenario(const std::string& path, ErrorList& errors) {
  const std::optional<std::string> text = file_text(path);
  if (!text) {
    errors.add(SourceError::at(path, 0, 0, "cannot open the scenario file " + path + ": " + why_unreadable(path)));
    return Scenario();
  }
  Scenario sc = parse_scenario(*text, path, errors);
  // The files it names, each checked at the line that names it, with the path it led to;
  // no cell is then built from them (its error would name neither).
  struct Named {
    const std::string& path;
    const SourceLocation& at;
    const char* key;
    const char* what;
  };
  for (const Named& n : {Named{sc.cell, sc.cell_at, "cell", "the cell config"},
                         Named{sc.program, sc.program_at, "program", "the program file"},
                         Named{sc.line, sc.line_at, "line", "the line file"}}) {
    const std::string why = n.path.empty() ? "" : why_unreadable(n.path);
    if (why.empty()) continue;
    errors.add(SourceError::at(n.at.file, n.at.line, n.at.column,
                               std::string("key '") + n.key + "': cannot open " + n.what + ": " + why));
    sc.cell.clear();
    sc.line.clear();
  }
  return sc;
}

Scenario load_scenario(const std::string& path) {
  ErrorList errors;
  Scenario sc = read_scenario(path, errors);
  errors.throw_if_any();
  return sc;
}

}  // namespace scenario
}  // namespace plc_cell
