#include "plc_cell/line/line_file.h"

#include <set>

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/file_text.h"
#include "plc_cell/core/unreadable.h"

namespace plc_cell {
namespace line {

namespace {

std::string folder_of(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

std::string resolved(const std::string& file, const std::string& p) {
  return !p.empty() && p[0] == '/' ? p : folder_of(file) + p;
}

SourceLocation where(const std::string& file, const YAML::Node& n) {
  return {file, YamlReader::line(n), n.Mark().is_null() ? 0 : n.Mark().column + 1};
}

// A delay, a travel or a length: a duration from 0 to an hour (a length above 0).
uint64_t span(const YamlReader& r, const YAML::Node& n, const std::string& key, bool positive) {
  const uint64_t us = r.duration_us(n, key);
  if (us > kMaxWireDelayUs) r.fail(n, key, "at most 3600 s");
  if (positive && us == 0) r.fail(n, key, "a part covers its sensor for some time: above 0");
  return us;
}

// robot: robot.yaml, or robot: {config: robot.yaml, program: robot.il, scan: 2ms}.
CellEntry read_cell(const YamlReader& r, const YAML::Node& name, const YAML::Node& n) {
  CellEntry c;
  const std::string key = "cells." + name.Scalar();
  c.name = r.topic_name(name, key, "cell");
  c.at = where(r.file(), name);
  if (n.IsMap()) {
    r.only(n, key, {"config", "program", "scan"});
    if (!n["config"]) r.fail(n, key, "missing 'config': the cell YAML");
    if (n["program"]) {
      c.program = resolved(r.file(), r.str(n["program"], key + ".program"));
      c.program_at = where(r.file(), n["program"]);
    }
    if (n["scan"]) {
      c.scan_us = r.duration_us(n["scan"], key + ".scan");
      if (c.scan_us < 100 || c.scan_us > 1000000) r.fail(n["scan"], key + ".scan", "a scan period is 0.1 ms to 1 s");
      c.scan_at = where(r.file(), n["scan"]);
    }
  } else if (!n.IsScalar()) {
    r.fail(n, key, "expected the cell YAML, or {config: CELL.yaml, program: FILE.il, scan: 1ms}");
  }
  // Not a Node assigned from another: yaml-cpp's assignment would overwrite n itself.
  const YAML::Node config = n.IsMap() ? n["config"] : n;
  c.config = resolved(r.file(), r.str(config, key + (n.IsMap() ? ".config" : "")));
  c.config_at = where(r.file(), config);
  return c;
}

WireEntry read_wire(const YamlReader& r, const YAML::Node& n, const std::string& key) {
  if (!n.IsMap()) r.fail(n, key, "a wire is a mapping: {from: CELL.NAME, to: CELL.NAME, delay: 2s}");
  r.only(n, key, {"from", "to", "delay", "invert", "part"});
  WireEntry w;
  w.at = where(r.file(), n);
  for (const char* end : {"from", "to"}) {
    const std::string k = key + "." + end;
    if (!n[end]) r.fail(n, key, std::string("missing '") + end + "': CELL.NAME, e.g. robot.part_in");
    std::string& text = std::string(end) == "from" ? w.from : w.to;
    text = r.str(n[end], k);
    std::string cell, rest;
    if (!split_qualified(text, &cell, &rest))
      r.fail(n[end], k, "'" + text + "': a wire's end is CELL.NAME (a signal or an address of the cell: robot.part_in, robot.X3)");
    (std::string(end) == "from" ? w.from_at : w.to_at) = where(r.file(), n[end]);
  }
  if (n["delay"]) w.delay_us = span(r, n["delay"], key + ".delay", false);
  if (n["invert"]) w.invert = r.boolean(n["invert"], key + ".invert");
  if (n["part"]) {
    const YAML::Node p = n["part"];
    const std::string k = key + ".part";
    if (n["delay"]) r.fail(n["delay"], key + ".delay", "a part's delay is its travel: part: {travel: 2s, length: 300ms}");
    if (!p.IsMap()) r.fail(p, k, "expected {travel: 2s, length: 300ms}");
    r.only(p, k, {"travel", "length"});
    if (!p["travel"] || !p["length"]) r.fail(p, k, "a part has a travel and a length: {travel: 2s, length: 300ms}");
    w.part = true;
    w.travel_us = span(r, p["travel"], k + ".travel", false);
    w.length_us = span(r, p["length"], k + ".length", true);
  }
  return w;
}

// The name a line has when its file gives none: the file's name up to its first '.'.
std::string stem(const std::string& file) {
  std::string s = file.substr(file.rfind('/') == std::string::npos ? 0 : file.rfind('/') + 1);
  return s.substr(0, s.find('.'));
}

}  // namespace

bool split_qualified(const std::string& name, std::string* cell, std::string* rest) {
  const auto dot = name.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == name.size()) return false;
  *cell = name.substr(0, dot);
  *rest = name.substr(dot + 1);
  return true;
}

LineFile parse_line_file(const std::string& text, const std::string& file, ErrorList& errors) {
  const YamlReader r(file);
  LineFile lf;
  lf.file = file;
  lf.name = stem(file);
  YAML::Node doc;
  if (!errors.collect([&] { doc = r.load(text); }, file)) return lf;
  if (!doc.IsMap()) {
    errors.add(SourceError::at(file, 1, 1, "a line file is a mapping with 'cells' and 'wires'"));
    return lf;
  }
  r.only(doc, "", {"line", "cells", "wires"}, &errors);
  if (doc["line"])
    errors.collect([&] {
      r.only(doc["line"], "line", {"name"});
      if (doc["line"]["name"]) lf.name = r.topic_name(doc["line"]["name"], "line.name", "line");
    }, file, doc["line"]);
  const YAML::Node cells = doc["cells"];
  if (!cells || !cells.IsMap() || cells.size() == 0)
    errors.add(ErrorList::diagnostic(file, cells ? cells : doc,
                                     "key 'cells': expected a mapping of cell names to cell YAMLs (robot: robot.yaml)"));
  std::set<std::string> names;
  if (cells && cells.IsMap())
    for (const auto& kv : cells)
      errors.collect([&] {
        CellEntry c = read_cell(r, kv.first, kv.second);
        if (!names.insert(c.name).second) r.fail(kv.first, "cells." + c.name, "a second cell named '" + c.name + "'");
        lf.cells.push_back(std::move(c));
      }, file, kv.first);
  const YAML::Node wires = doc["wires"];  // none (or `wires:` alone): cells side by side
  if (wires && !wires.IsNull() && !wires.IsSequence())
    errors.add(ErrorList::diagnostic(file, wires, "key 'wires': expected a list of {from: CELL.NAME, to: CELL.NAME}"));
  if (wires && wires.IsSequence())
    for (size_t i = 0; i < wires.size(); ++i)
      errors.collect([&] { lf.wires.push_back(read_wire(r, wires[i], "wires[" + std::to_string(i) + "]")); }, file,
                     wires[i]);
  return lf;
}

LineFile read_line_file(const std::string& path, ErrorList& errors) {
  const std::optional<std::string> text = file_text(path);
  if (!text) {
    errors.add(SourceError::at(path, 0, 0, "cannot open the line file " + path + ": " + why_unreadable(path)));
    LineFile lf;
    lf.file = path;
    return lf;
  }
  return parse_line_file(*text, path, errors);
}

LineFile load_line_file(const std::string& path) {
  ErrorList errors;
  LineFile f = read_line_file(path, errors);
  errors.throw_if_any();
  return f;
}

}  // namespace line
}  // namespace plc_cell
