#pragma once
// The cells one monitor serves (docs/monitor.md, "One monitor for a line"): each a named
// Source, with the wires between them as their line file writes them. A single cell's
// monitor is the set of one; a line's (`plc_cell run --line`, a line's recording) has one
// source per cell, each with its own ladder page under /cell/NAME/, and an overview.
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/monitor/property_board.h"
#include "plc_cell/monitor/source.h"

namespace plc_cell {
namespace monitor {

// A wire between two cells of the set, its ends as the line file names them
// ("infeed.release", "robot.nest_sensor"); text is how the line describes it
// ("infeed.release -> robot.nest_sensor (part ...)").
struct SetWire {
  std::string from, to, text;
};

// A qualified name's cell and the address it names there (SourceSet::locate).
struct Located {
  size_t cell = 0;
  Address address;
};

class SourceSet {
 public:
  // name: the first part of each qualified name (robot.X3) and the page's /cell/NAME/;
  // letters, digits, '_' and '-' only (throws Error naming it otherwise, or a second one).
  void add(const std::string& name, Source& source);
  void add(const std::string& name, std::unique_ptr<Source> source);
  void add_wire(SetWire w) { wires_.push_back(std::move(w)); }
  void set_title(std::string t) { title_ = std::move(t); }
  // The properties watched over these cells, which the overview shows (nullptr: none).
  void watch(std::shared_ptr<const PropertyBoard> board) { properties_ = std::move(board); }
  const PropertyBoard* properties() const { return properties_.get(); }
  // A lone cell's monitor, as it was before sets: its page at /, no overview page (the
  // server of one Source). A set of one cell otherwise still opens on the overview (a line
  // of one, the one nodelet of a process).
  void serve_alone() { alone_ = true; }
  bool alone() const { return alone_; }

  size_t size() const { return cells_.size(); }
  const std::string& name(size_t i) const { return cells_[i].name; }
  Source& source(size_t i) const { return *cells_[i].source; }
  const std::vector<SetWire>& wires() const { return wires_; }
  const std::string& title() const { return title_; }  // the line's name ("" for a lone cell)
  // The index of the cell named name, or -1.
  int find(const std::string& name) const;
  std::string names() const;  // "infeed, robot, test"

  // "robot.X3" or "robot.part_in": true with the cell and its address when the part before
  // the first '.' names a cell of the set; false when it names none (a name of the page's
  // own cell). Throws Error when the cell is there but the rest names nothing in it.
  bool locate(const std::string& text, Located* out) const;

 private:
  struct Entry {
    std::string name;
    Source* source = nullptr;
    std::unique_ptr<Source> owned;
  };
  std::vector<Entry> cells_;
  std::vector<SetWire> wires_;
  std::string title_;
  std::shared_ptr<const PropertyBoard> properties_;
  bool alone_ = false;
};

}  // namespace monitor
}  // namespace plc_cell
