#pragma once
// A line file (docs/lines.md): the cells of a line, each a name and a cell YAML (with, in
// its place, an optional program and scan period), and the wires between them. Reading
// checks the file's own shape; what its names mean in each cell is checked when the line
// is built (line.h). Every error carries the file:line:column that caused it.
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/config/error_list.h"
#include "plc_cell/core/error.h"

namespace plc_cell {
namespace line {

struct CellEntry {
  std::string name;     // "robot": the first part of every name of the cell (robot.part_in)
  std::string config;   // the cell YAML, resolved against the line file's folder
  std::string program;  // resolved the same way; empty: the cell YAML's cell.program
  uint64_t scan_us = 0; // 0: the cell YAML's plc.scan_period
  SourceLocation at, config_at, program_at, scan_at;
};

// A wire (docs/lines.md, "Wires"): the value of `from` sampled at the end of each scan of
// its cell, delivered to `to` after delay_us (inverted when invert); or, with a part, each
// rising edge of `from` a part that travels travel_us and then covers `to` for length_us.
struct WireEntry {
  std::string from, to;  // qualified names as written: "infeed.part_out", "robot.X3"
  uint64_t delay_us = 0;
  bool invert = false;
  bool part = false;
  uint64_t travel_us = 0, length_us = 0;
  SourceLocation at, from_at, to_at;
};

struct LineFile {
  std::string file;
  std::string name;              // line.name, else the file's name up to its first '.'
  std::vector<CellEntry> cells;  // in file order: the order the cells scan at one instant
  std::vector<WireEntry> wires;  // in file order
};

// The longest delay, travel or part length a wire takes.
constexpr uint64_t kMaxWireDelayUs = 3600ULL * 1000000ULL;

// What can be read of the file, every error into errors (nothing thrown for the file's
// content; a file that cannot be opened is one error at its line 0).
LineFile read_line_file(const std::string& path, ErrorList& errors);
LineFile parse_line_file(const std::string& text, const std::string& file, ErrorList& errors);
// The same, every error of the file thrown as one SourceError.
LineFile load_line_file(const std::string& path);

// "robot.part_in" -> {"robot", "part_in"}; false when there is no '.' or either side is empty.
bool split_qualified(const std::string& name, std::string* cell, std::string* rest);

}  // namespace line
}  // namespace plc_cell
