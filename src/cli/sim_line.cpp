// plc_cell sim --line: a line of cells on one virtual clock (docs/lines.md), with the watched
// names of any cell printed at the end, their changes traced, the whole run recorded.
#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>

#include "cell_options.h"
#include "record_option.h"
#include "plc_cell/core/error.h"
#include "plc_cell/line/line.h"
#include "plc_cell/sim/virtual_run.h"

namespace plc_cell {
namespace cli {

namespace {

constexpr uint64_t kTracePieceInstants = 65536;

struct LineWatch {
  std::string name;  // as given: "robot.count:u"
  size_t cell;
  Address a;
  ValueFormat format;
  uint32_t last = 0;
  bool seen = false;
};

// CELL.REST of a line: the cell's index and REST, or a UsageError naming the option.
size_t cell_of(line::Line& l, const std::string& option, const std::string& text, std::string* rest) {
  std::string cell;
  if (!line::split_qualified(text, &cell, rest))
    throw UsageError(option + " " + text + ": a line's names are CELL.NAME (cells: " + l.names() + ")");
  const int i = l.find(cell);
  if (i < 0) throw UsageError(option + " " + text + ": no cell '" + cell + "' in the line (" + l.names() + ")");
  return size_t(i);
}

std::vector<LineWatch> line_watches(const Args& args, line::Line& l) {
  std::vector<LineWatch> out;
  for (const auto& w : args.all("watch"))
    for (const auto& n : split_list(w)) {
      LineWatch lw;
      lw.name = n;
      std::string rest;
      lw.cell = cell_of(l, "--watch", n, &rest);
      try {
        const auto nf = split_format(rest);
        lw.a = l.cell(lw.cell)->config().resolve(nf.first);
        lw.format = nf.second;
        check_format(lw.a, lw.format, n);
      } catch (const Error& e) {
        throw Error("--watch " + n + ": " + e.what());
      }
      out.push_back(lw);
    }
  return out;
}

// The trace's rows, one for each change of a watched name at the end of its cell's scan, in
// the order of the instants and, at one instant, of the cells in the file. The line runs
// cell by cell over windows of instants (line.h, advance): each cell's rows come in its own
// order and are put in the line's before they are written.
class LineTrace {
 public:
  explicit LineTrace(const std::string& path) : out_(path) {
    if (!out_) throw Error("cannot write the trace file " + path);
    out_ << "time_s,name,value\n";
  }
  void row(uint64_t t_us, size_t cell, std::string text) { rows_.push_back({t_us, cell, std::move(text)}); }
  void flush() {
    std::stable_sort(rows_.begin(), rows_.end(),
                     [](const Row& a, const Row& b) { return a.t_us != b.t_us ? a.t_us < b.t_us : a.cell < b.cell; });
    for (const Row& r : rows_) out_ << r.text;
    rows_.clear();
  }

 private:
  struct Row {
    uint64_t t_us;
    size_t cell;
    std::string text;
  };
  std::ofstream out_;
  std::vector<Row> rows_;
};

}  // namespace

int sim_line(const Args& args) {
  for (const char* o : {"config", "program", "scan", "rtc-start"})
    if (args.has(o)) throw UsageError(std::string("--") + o + " goes with a cell, not --line: a line file names its cells'");
  const uint64_t duration = parse_duration_us(args.require("duration"));
  line::LineOptions o;
  if (args.has("engine")) o.run.push_back({"", "engine", {args.get("engine")}, "--engine"});
  line::Line l(args.get("line"), o);
  for (size_t i = 0; i < l.size(); ++i)
    for (const auto& w : l.cell(i)->soft().warnings()) std::cerr << w.to_string() << "\n";  // the run goes on
  l.run();
  for (const auto& s : args.all("set")) {
    std::string rest;
    apply_set(*l.cell(cell_of(l, "--set", s, &rest)), rest, s);
  }
  std::vector<LineWatch> watches = line_watches(args, l);
  std::unique_ptr<LineTrace> trace = args.has("trace") ? std::make_unique<LineTrace>(args.get("trace")) : nullptr;
  // The watched names of each cell, read after each of its scans; a change is a trace row.
  std::vector<std::vector<size_t>> by_cell(l.size());
  for (size_t k = 0; k < watches.size(); ++k) by_cell[watches[k].cell].push_back(k);
  const auto rec = args.has("record") ? record_line(l, "plc_cell sim --line " + args.get("line")) : nullptr;
  recording::LineRecorder* r = rec.get();
  // A cell's own values only: the line may run cell by cell.
  l.after_scan([&](size_t i, uint64_t t) {
    if (r) r->cell(i).scanned(l.cell(i)->plc(), t);
    if (by_cell[i].empty()) return;
    l.cell(i)->plc().locked([&](ScanEngine&, Memory& m) {
      for (size_t k : by_cell[i]) {
        LineWatch& w = watches[k];
        const uint32_t v = m.read(w.a);
        if (w.seen && v == w.last) continue;
        w.seen = true;
        w.last = v;
        if (trace) trace->row(t, i, seconds(t) + "," + w.name + "," + format_value(w.a, v, w.format) + "\n");
      }
      return 0;
    });
  }, line::Line::Observer::PerCell);
  const uint64_t instants = (duration + l.tick_us() - 1) / l.tick_us();
  // In pieces, so that the trace's rows wait in memory for one piece at the most.
  const uint64_t piece = kTracePieceInstants * l.tick_us();
  for (uint64_t t = 0; t < instants * l.tick_us(); t += piece) {
    l.advance(t, std::min(t + piece, instants * l.tick_us()));
    if (trace) trace->flush();
  }
  if (rec) rec->save(args.get("record"));

  std::cout << "# plc_cell sim: line " << l.name() << ", " << l.size() << " cells, " << instants << " instants of "
            << l.tick_us() << " us, virtual time " << seconds(instants * l.tick_us()) << " s\n";
  for (size_t i = 0; i < l.size(); ++i) {
    Plc& plc = l.cell(i)->plc();
    const uint64_t scans = plc.locked([](ScanEngine& e, Memory&) { return e.stats().scans; });
    std::cout << "#   " << l.entry(i).name << ": " << scans << " scans of " << l.period_us(i) << " us, "
              << (plc.mode() == RunMode::Run ? "RUN" : "STOP") << "\n";
  }
  const std::string fault = l.fault();
  if (!fault.empty()) std::cout << "# fault: " << fault << "\n";
  for (const auto& w : watches) {
    const uint32_t v = l.cell(w.cell)->plc().locked([&](ScanEngine&, Memory& m) { return m.read(w.a); });
    std::cout << w.name << " = " << format_value(w.a, v, w.format) << "\n";
  }
  return fault.empty() ? 0 : 1;
}

}  // namespace cli
}  // namespace plc_cell
