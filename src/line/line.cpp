#include "plc_cell/line/line.h"

#include <numeric>

#include "diagnostic_at.h"
#include "plc_cell/core/unreadable.h"

namespace plc_cell {
namespace line {

namespace {

// The cell YAML of a cell built elsewhere: read for its names and its simulation only.
CellConfig config_only(const CellEntry& c, ErrorList& errors) {
  CellConfig cfg;
  errors.collect([&] { cfg = load_cell_config(c.config, &errors, Cell::sections()); }, c.config);
  return cfg;
}

}  // namespace

Line::Line(const std::string& path, LineOptions options) : Line(load_line_file(path), std::move(options)) {}

Line::Line(const LineFile& file, LineOptions options) : file_(file), options_(std::move(options)) {
  ErrorList errors;
  build(errors);
  errors.throw_if_any();
}

Line::~Line() {
  stop();
  sinks_.clear();  // their hooks leave the cells' engines before the cells go
  twin_sinks_.clear();
}

int Line::find(const std::string& name) const {
  for (size_t i = 0; i < file_.cells.size(); ++i)
    if (file_.cells[i].name == name) return int(i);
  return -1;
}

std::string Line::names() const {
  std::string s;
  for (const auto& c : file_.cells) s += (s.empty() ? "" : ", ") + c.name;
  return s;
}

// Every cell, each error of one not stopping the others: a user fixes the whole line at once.
void Line::build(ErrorList& errors) {
  const size_t n = file_.cells.size();
  for (const auto& name : options_.here)
    if (find(name) < 0) throw Error("line " + file_.name + " has no cell '" + name + "' to build here (" + names() + ")");
  cells_.resize(n);
  periods_.assign(n, 0);
  std::vector<CellConfig> configs(n);
  std::vector<bool> ok(n, false);
  for (size_t i = 0; i < n; ++i) {
    const CellEntry& c = file_.cells[i];
    const std::string why = why_unreadable(c.config);
    if (!why.empty()) {
      errors.add(error_at(c.config_at, "key 'cells." + c.name + "': cannot open the cell YAML: " + why));
      continue;
    }
    if (!c.program.empty() && !why_unreadable(c.program).empty()) {
      errors.add(error_at(c.program_at, "key 'cells." + c.name + ".program': cannot open the program: " +
                                            why_unreadable(c.program)));
      continue;
    }
    if (!options_.here.empty() && !options_.here.count(c.name)) {
      configs[i] = config_only(c, errors);
      periods_[i] = c.scan_us ? c.scan_us : configs[i].scan_period_us;
      ok[i] = true;
      continue;
    }
    CellOverrides o;
    o.program = c.program;
    if (c.scan_us)
      o.run.push_back({"", "scan_period", {std::to_string(c.scan_us) + "us"}, "cells." + c.name + ".scan"});
    for (const auto& r : options_.run) o.run.push_back(r);
    try {
      cells_[i] = std::make_unique<Cell>(c.config, o, options_.purpose, options_.log);
      configs[i] = cells_[i]->config();
      periods_[i] = cells_[i]->scan_period_us();
      ok[i] = true;
    } catch (const SourceError& e) {
      errors.add(e);  // at the cell YAML's or the program's own lines
    } catch (const Error& e) {
      errors.add(error_at(c.at, "cell " + c.name + ": " + e.what()));
    }
  }
  uint64_t g = 0;
  for (size_t i = 0; i < n; ++i)
    if (here(i)) g = std::gcd(g, periods_[i]);
  tick_us_ = g ? g : 1000;
  // A wire is checked only against cells that were read: an error in a cell YAML is not
  // repeated as one error per wire that names it.
  std::vector<const CellConfig*> read(n, nullptr);
  for (size_t i = 0; i < n; ++i)
    if (ok[i]) read[i] = &configs[i];
  resolve_wires(read, errors);
}

}  // namespace line
}  // namespace plc_cell
