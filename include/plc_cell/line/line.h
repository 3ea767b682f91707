#pragma once
// A line of cells (docs/lines.md): the cells of a line file, each a Cell of its own built
// from its cell YAML, and the wires between them, carried in this process.
//
// In virtual time one clock runs every cell: scan_at(t) scans, in the order of the line
// file, each cell whose period divides t, and what each wire's source sampled at the end of
// its scan reaches the wire's sink end before the sink's next scan, which delivers it at its
// instant. A scan reads its inputs at its instant, before any cell's outputs of that
// instant, so the order of the cells at one instant decides nothing a cell sees: the same
// file gives the same run, scan for scan, whatever its order (docs/lines.md, "One clock").
// advance() gives the same scans taken cell by cell over windows of instants.
//
// In real time each cell scans on its own thread (or cells share threads, as nodelets do),
// and each source's thread carries its wires after its scans; a sink then counts the delay
// from the value's arrival on its own clock.
//
// A line may be built in part (LineOptions::here): the cells named there are built, the
// others only read (their YAMLs, to check the wires), and a wire with one end elsewhere is
// half here. Its source end hands its samples to on_remote_sample(); whoever carries them
// (a ROS topic) gives them to the process of the sink end, whose line takes them with
// receive(). The wire's model is the same on both sides (delay_line.h).
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "plc_cell/core/realtime_loop.h"
#include "plc_cell/line/delay_line.h"
#include "plc_cell/line/line_file.h"
#include "plc_cell/line/wire_sink.h"
#include "plc_cell/line/wire_taps.h"
#include "plc_cell/runtime/cell.h"

namespace plc_cell {
namespace line {

struct LineOptions {
  Cell::Purpose purpose = Cell::Purpose::Simulate;
  // Run settings for every cell (--engine), after the line file's own (a cell's scan).
  std::vector<SettingOverride> run;
  // The cells built in this process; empty: every cell.
  std::set<std::string> here;
  std::function<void(const std::string&)> log;  // each cell's store's events
};

// A wire as built: its entry in the file, its ends resolved in their cells.
struct Wire {
  WireEntry entry;
  size_t from_cell = 0, to_cell = 0;
  Address from, to;
  WireModel model;
  uint32_t initial = 0;  // the source's value before the first scan
};

class Line {
 public:
  // Throws SourceError listing every error of the line file, of the cell YAMLs and programs
  // (at their own file:line) and of the wires (at the line file's).
  explicit Line(const std::string& path, LineOptions options = {});
  Line(const LineFile& file, LineOptions options);
  ~Line();  // stops the scans; the wires' ends leave the cells before the cells go
  Line(const Line&) = delete;
  Line& operator=(const Line&) = delete;

  const std::string& name() const { return file_.name; }
  const std::string& file() const { return file_.file; }
  // Every cell of the file, built here or not, in file order.
  size_t size() const { return file_.cells.size(); }
  const CellEntry& entry(size_t i) const { return file_.cells[i]; }
  // The cell built here, or nullptr.
  Cell* cell(size_t i) { return cells_[i].get(); }
  // The index of the cell named name, or -1.
  int find(const std::string& name) const;
  // "infeed, robot, test": the cells' names, for messages.
  std::string names() const;
  const std::vector<Wire>& wires() const { return wires_; }
  // The cell's scan period (here or not).
  uint64_t period_us(size_t i) const { return periods_[i]; }
  // The grid every instant of the line lies on: the greatest common divisor of the scan
  // periods of the cells here.
  uint64_t tick_us() const { return tick_us_; }

  // ---- virtual time ----
  // Puts every cell here in RUN and connects the wires' ends (throws Error naming a cell
  // that cannot RUN). Before the first scan_at.
  void run();
  // Every cell here whose period divides t_us scans at t_us, in file order, then the wires
  // carry what they sampled. t_us on the tick grid, increasing.
  void scan_at(uint64_t t_us);
  // Every instant of [from_us, to_us) on the tick grid, from_us on it: the same scans with
  // the same results as scan_at at each instant in turn, but taken cell by cell over a
  // window of instants where the wires allow it (line_schedule.cpp), so that a cell stays in
  // the caches for many scans. Instant by instant when an observer needs the whole line at
  // each instant (after_scan with Observer::Line) or wires leave the process.
  void advance(uint64_t from_us, uint64_t to_us);
  // What an after_scan observer reads: the whole line (every cell at the instant of the call:
  // the line then runs instant by instant), or only the cell it is called for (each cell's
  // scans come in order, but one cell may be ahead of another).
  enum class Observer { Line, PerCell };
  // Called after each scan of a cell, with its index and instant (recordings, traces), once
  // its wires are carried. In real time on the cell's scan thread, with no lock held: for
  // two cells on two threads, at the same time. Set it before the line runs.
  void after_scan(std::function<void(size_t cell, uint64_t t_us)> f, Observer reads = Observer::Line) {
    after_scan_ = std::move(f);
    observer_ = reads;
  }
  // "robot: <why>" for the first cell here (in file order) that stopped on a fault; "" if none.
  std::string fault();

  // ---- real time ----
  // Every cell here in RUN and scanned at its period: on its own thread (shared_threads 0),
  // or all of them on that many shared scan threads (SharedScanThread).
  void start_real_time(unsigned shared_threads = 0);
  // The scans stop, then the servers; idempotent (the destructor calls it).
  void stop();

  // ---- wires across processes ----
  // A wire whose source is here and sink elsewhere: each change, with its scan's instant.
  // Called on the scanning thread, with no lock held: in real time, for two cells on two
  // threads at the same time. Set it before the line runs.
  void on_remote_sample(std::function<void(size_t wire, uint64_t t_us, uint32_t value)> f) {
    on_remote_ = std::move(f);
  }
  // A wire whose sink is here and source elsewhere: the source's value arrives now (the
  // sink's last scan instant on its own clock starts the delay). Any thread.
  void receive(size_t wire, uint32_t value);
  // The same at t_us of the sink's clock (a carrier in virtual time: the sample's instant,
  // which the one clock of the line's processes shares). Throws Error for a wire whose sink
  // is not here.
  void receive(size_t wire, uint64_t t_us, uint32_t value);

 private:
  void build(ErrorList& errors);
  // configs: each cell's, read here or built; nullptr for one that could not be read.
  void resolve_wires(const std::vector<const CellConfig*>& configs, ErrorList& errors);
  bool resolve_end(const std::vector<const CellConfig*>& configs, const std::string& text, const SourceLocation& at,
                   size_t* cell, Address* a, ErrorList& errors) const;
  Diagnostic refused_wire(const Wire& w, const CellConfig& to_cfg);
  void connect();
  void carry(size_t cell);  // the samples cell's taps took, to their sinks
  // Virtual time: cell i scans at t_us if it is due then, its inbox delivered first.
  void scan_cell(size_t i, uint64_t t_us);
  // The samples for cell i that the instant-by-instant order delivers before its scan at t_us.
  void take_inbox(size_t i, uint64_t t_us);
  // The cells here in groups (line_schedule.cpp): cells that wires join in a cycle share one,
  // and every wire between two groups goes from an earlier group to a later one.
  void group_cells();
  void deliver(size_t wire, uint64_t t_us, uint32_t value);
  bool here(size_t i) const { return cells_[i] != nullptr; }

  LineFile file_;
  LineOptions options_;
  std::vector<std::unique_ptr<Cell>> cells_;  // nullptr: elsewhere
  std::vector<uint64_t> periods_;
  std::vector<uint64_t> due_us_;  // per cell here: its next scan's instant
  uint64_t tick_us_ = 1000;
  std::vector<Wire> wires_;
  // Per cell here: the taps of the wires leaving it, and which wire each tap is.
  std::vector<WireTaps> taps_;
  std::vector<std::vector<size_t>> tap_wire_;
  // Per wire: its sink end when the sink is here (destroyed before the cells: see ~Line),
  // and the same in the sink's lockstep twin (runtime/cell.h), which every value reaches too.
  std::vector<std::unique_ptr<WireSink>> sinks_, twin_sinks_;
  std::function<void(size_t, uint64_t)> after_scan_;
  Observer observer_ = Observer::Line;
  // Virtual time: per sink cell here, the samples of its wires not yet delivered, each with
  // its source's instant and cell. A sink takes them just before its next scan, so the order
  // the cells scan in changes nothing it sees.
  struct Inbound {
    uint64_t t_us;
    size_t from_cell, wire;
    uint32_t value;
  };
  std::vector<std::vector<Inbound>> inbox_;
  std::vector<std::vector<size_t>> groups_;
  std::function<void(size_t, uint64_t, uint32_t)> on_remote_;
  std::vector<std::pair<SharedScanThread*, uint64_t>> shared_;  // in real time on shared threads
  bool real_time_ = false;
};

}  // namespace line
}  // namespace plc_cell
