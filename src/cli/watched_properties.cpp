#include "watched_properties.h"

#include <climits>
#include <cstdlib>

#include "plc_cell/core/error.h"
#include "plc_cell/line/line_properties.h"
#include "plc_cell/recording/image.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/scenario_file.h"

namespace plc_cell {
namespace cli {

namespace {

std::string real_path(const std::string& p) {
  char buf[PATH_MAX];
  return ::realpath(p.c_str(), buf) ? std::string(buf) : p;
}

// The scenario file, which must be a line's (the one `same_line` accepts) and have properties.
scenario::Scenario line_scenario(const std::string& path, const std::string& what,
                                 const std::function<bool(const scenario::Scenario&)>& same_line) {
  const scenario::Scenario sc = scenario::load_scenario(path);
  if (sc.line.empty())
    throw SourceError::at(sc.cell_at.file.empty() ? path : sc.cell_at.file, sc.cell_at.line, sc.cell_at.column,
                          "--properties: this file's properties are a cell's (cell:); " + what +
                              " is watched with a line's (line:)");
  if (!same_line(sc))
    throw SourceError::at(sc.line_at.file, sc.line_at.line, sc.line_at.column,
                          "--properties: line: " + sc.line + " is not " + what);
  if (sc.properties.empty()) throw SourceError::at(path, 1, 1, "--properties: the file has no properties: to watch");
  return sc;
}

// A name of a property: its cell of the monitor's set and its address there.
std::function<scenario::WatchedAddress(const scenario::Probe&)> in_set(const monitor::SourceSet& set) {
  return [&set](const scenario::Probe& p) {
    if (p.kind != scenario::Probe::Kind::Address)
      throw Error("'" + p.text + "': the monitor watches addresses and signals; a " + p.family +
                  ". reading is a test's (plc_cell test)");
    if (set.find(p.cell) < 0) throw Error("'" + p.text + "': no cell '" + p.cell + "' here (" + set.names() + ")");
    monitor::Located at;
    set.locate(p.cell + "." + p.name, &at);
    return scenario::WatchedAddress{at.cell, at.address};
  };
}

// Feeds w every scan of r's cells in time order (file order at one instant), each cell's
// names rebuilt from its recorded changes.
void replay_into(const recording::LineReader& r, scenario::PropertyWatcher& w) {
  struct Cell {
    std::vector<std::vector<uint32_t>> cells;    // per address: its recording cells
    std::vector<std::vector<uint16_t>> values;   // and their values
    std::vector<uint32_t> raw;
    size_t next = 0;
  };
  std::vector<Cell> cs(r.size());
  for (size_t c = 0; c < r.size(); ++c) {
    const recording::Image& img = r.cell(c).initial();
    for (const Address& a : w.addresses(c)) {
      cs[c].cells.push_back(recording::cells_of(a));
      std::vector<uint16_t> v;
      for (uint32_t n : cs[c].cells.back()) v.push_back(n < recording::bit_cells() ? img.bits[n] : img.words[n - recording::bit_cells()]);
      cs[c].values.push_back(v);
    }
    cs[c].raw.resize(w.addresses(c).size());
  }
  for (;;) {
    size_t c = r.size();
    for (size_t i = 0; i < r.size(); ++i)
      if (cs[i].next < r.cell(i).scans() && (c == r.size() || r.cell(i).scan_us(cs[i].next) < r.cell(c).scan_us(cs[c].next)))
        c = i;
    if (c == r.size()) break;
    Cell& cell = cs[c];
    const size_t scan = cell.next++;
    r.cell(c).each_change(scan, scan, [&](size_t, uint32_t n, uint16_t value) {
      for (size_t k = 0; k < cell.cells.size(); ++k)
        for (size_t j = 0; j < cell.cells[k].size(); ++j)
          if (cell.cells[k][j] == n) cell.values[k][j] = value;
      return true;
    });
    for (size_t k = 0; k < cell.raw.size(); ++k) cell.raw[k] = recording::value_of(w.addresses(c)[k], cell.values[k]);
    w.scanned(c, r.cell(c).scan_us(scan), cell.raw.data());
  }
  w.flush();
}

}  // namespace

std::shared_ptr<scenario::PropertyWatcher> watch_line(const std::string& path, line::Line& l,
                                                      const monitor::SourceSet& set) {
  const scenario::Scenario sc = line_scenario(path, "the line run (" + l.file() + ")", [&](const scenario::Scenario& s) {
    return real_path(s.line) == real_path(l.file());
  });
  // The watcher numbers the cells as the line does (watch_properties reads them by it).
  const auto resolve = [&](const scenario::Probe& p) {
    scenario::WatchedAddress at = in_set(set)(p);
    at.cell = size_t(l.find(p.cell));
    return at;
  };
  auto w = std::make_shared<scenario::PropertyWatcher>(sc.properties, resolve, path,
                                                       "evaluated after every scan of every cell of the line");
  line::watch_properties(l, w);
  return w;
}

std::shared_ptr<scenario::PropertyWatcher> watch_recording(const std::string& path, const recording::LineReader& r,
                                                           const monitor::SourceSet& set) {
  const scenario::Scenario sc =
      line_scenario(path, "line " + r.info().line + " (the recording's)",
                    [&](const scenario::Scenario& s) { return line::load_line_file(s.line).name == r.info().line; });
  auto w = std::make_shared<scenario::PropertyWatcher>(sc.properties, in_set(set), path,
                                                       "evaluated over every recorded scan up to the replay cursor", true);
  replay_into(r, *w);
  return w;
}

std::string property_summary(const monitor::PropertyReport& r, const std::string& prefix) {
  std::string out;
  for (const auto& p : r.properties) {
    out += prefix + "property " + p.text + ": violations: " + std::to_string(p.violations);
    if (p.violations)
      out += ", last at " + scenario::format_time(p.last_begin_us) + " for " +
             scenario::format_time(p.last_duration_us) + (p.last_ongoing ? " (going on)" : "");
    out += "\n";
  }
  return out;
}

}  // namespace cli
}  // namespace plc_cell
