// The order a line's cells are scanned in over a window of instants (Line::advance).
//
// Instant by instant, every cell scans once an instant, one after the other: a line of 100
// cells brings each cell back into the caches 100 cells later, and past the caches every
// scan waits on memory. A cell sees another only through the wires, and a sink takes a
// sample only before its scan after the sample's instant (line_run.cpp, take_inbox). So a
// source may run a whole window ahead of its sinks: they find its samples waiting, in the
// order they would have come. Cells that wires join in a cycle cannot: each waits on the
// other's scans, so they share a group and take the window instant by instant, together.
// The groups go in an order where every wire between two groups goes forward (a
// topological order of the groups); any such order gives the same scans.
#include <algorithm>

#include "plc_cell/core/error.h"
#include "plc_cell/line/line.h"

namespace plc_cell {
namespace line {

namespace {

// A window of this many instants per group: long enough that a cell's return into the
// caches is paid once in thousands of scans, short enough that the samples waiting in the
// inboxes stay few.
constexpr uint64_t kWindowInstants = 8192;

// Tarjan's strongly connected components, iterative (a line of thousands of cells in a chain
// would recurse that deep). Components come out sinks first.
class Components {
 public:
  explicit Components(const std::vector<std::vector<size_t>>& next) : next_(next), index_(next.size(), kNone),
                                                                       low_(next.size(), 0), on_(next.size(), false) {}

  std::vector<std::vector<size_t>> run(const std::vector<size_t>& nodes) {
    for (size_t v : nodes)
      if (index_[v] == kNone) visit(v);
    return std::move(out_);
  }

 private:
  static constexpr size_t kNone = SIZE_MAX;

  void open(size_t v) {
    index_[v] = low_[v] = counter_++;
    stack_.push_back(v);
    on_[v] = true;
    frames_.push_back({v, 0});
  }

  void visit(size_t root) {
    open(root);
    while (!frames_.empty()) {
      Frame& f = frames_.back();
      if (f.edge < next_[f.v].size()) {
        const size_t w = next_[f.v][f.edge++];
        if (index_[w] == kNone) open(w);
        else if (on_[w]) low_[f.v] = std::min(low_[f.v], index_[w]);
        continue;
      }
      const size_t v = f.v;
      frames_.pop_back();
      if (!frames_.empty()) low_[frames_.back().v] = std::min(low_[frames_.back().v], low_[v]);
      if (low_[v] != index_[v]) continue;
      std::vector<size_t> component;
      size_t w;
      do {
        w = stack_.back();
        stack_.pop_back();
        on_[w] = false;
        component.push_back(w);
      } while (w != v);
      std::sort(component.begin(), component.end());  // file order within a group
      out_.push_back(std::move(component));
    }
  }

  struct Frame {
    size_t v, edge;
  };
  const std::vector<std::vector<size_t>>& next_;
  std::vector<size_t> index_, low_;
  std::vector<bool> on_;
  std::vector<size_t> stack_;
  std::vector<Frame> frames_;
  std::vector<std::vector<size_t>> out_;
  size_t counter_ = 0;
};

}  // namespace

void Line::group_cells() {
  std::vector<std::vector<size_t>> next(size());
  for (const Wire& w : wires_)
    if (here(w.from_cell) && here(w.to_cell)) next[w.from_cell].push_back(w.to_cell);
  std::vector<size_t> nodes;
  for (size_t i = 0; i < size(); ++i)
    if (here(i)) nodes.push_back(i);
  groups_ = Components(next).run(nodes);
  std::reverse(groups_.begin(), groups_.end());  // sources first
}

void Line::advance(uint64_t from_us, uint64_t to_us) {
  if (due_us_.size() != cells_.size()) throw Error("line " + name() + ": advance before run()");
  const uint64_t tick = tick_us_;
  // Samples leaving the process, or an observer of the whole line, need every cell at each
  // instant before the next.
  if (on_remote_ || (after_scan_ && observer_ == Observer::Line)) {
    for (uint64_t t = from_us; t < to_us; t += tick) scan_at(t);
    return;
  }
  for (uint64_t start = from_us; start < to_us;) {
    const uint64_t end = std::min(to_us, start + kWindowInstants * tick);
    for (const std::vector<size_t>& group : groups_)
      for (uint64_t t = start; t < end; t += tick)
        for (size_t i : group) scan_cell(i, t);
    start = end;
  }
}

}  // namespace line
}  // namespace plc_cell
