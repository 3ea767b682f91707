#pragma once
// Helpers of the ladder tests: a program laid out from its IL text, and lookups of its
// elements and wires by what the IL says, not by id.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/il_parser.h"
#include "plc_cell/ladder/layout.h"

namespace plc_cell {
namespace ladder {
namespace test {

inline const FunctionTable& functions() {
  static const FunctionTable fns = FunctionTable::with_core_functions();
  return fns;
}

inline Layout lay(const std::string& text, const Signals& signals = {}) {
  const Program p = parse_program(text, "t.il", functions());
  return layout(p, text, signals, &functions());
}

// The first network of a program.
inline Network net0(const std::string& text, const Signals& signals = {}) { return lay(text, signals).networks.at(0); }

// The one element showing this address (a contact or an output); fails the test otherwise.
inline const Element& at(const Network& n, const std::string& address, const std::string& type = "") {
  const Element* found = nullptr;
  for (const Element& e : n.elements)
    if (e.address == address && (type.empty() || e.type == type)) {
      EXPECT_EQ(found, nullptr) << "two elements show " << address;
      found = &e;
    }
  if (!found) ADD_FAILURE() << "no element shows " << address;
  static const Element none;
  return found ? *found : none;
}

inline ::testing::AssertionResult cell(const Network& n, const std::string& address, int row, int col) {
  const Element& e = at(n, address);
  if (e.row == row && e.col == col) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << address << " is at (" << e.row << ", " << e.col << "), expected ("
                                       << row << ", " << col << ")";
}

inline bool hwire(const Network& n, int row, int from, int to) {
  for (const Wire& w : n.wires)
    if (!w.vertical && w.row == row && w.from == from && w.to == to) return true;
  return false;
}

inline bool vwire(const Network& n, int col, int from, int to) {
  for (const Wire& w : n.wires)
    if (w.vertical && w.col == col && w.from == from && w.to == to) return true;
  return false;
}

// Every element in a cell of its own inside the grid, contacts left of the outputs' column.
inline void expect_a_sound_grid(const Network& n) {
  std::set<std::pair<int, int>> cells;
  for (const Element& e : n.elements) {
    EXPECT_TRUE(cells.insert({e.row, e.col}).second) << "network " << n.index << ": two elements at (" << e.row
                                                     << ", " << e.col << ")";
    EXPECT_GE(e.row, 0);
    EXPECT_LT(e.row, n.rows);
    EXPECT_EQ(e.type == "contact" ? e.col < n.cols : e.col == n.cols, true)
        << "network " << n.index << ": " << e.type << " " << e.address << " at column " << e.col;
  }
  for (const Wire& w : n.wires) {
    EXPECT_LT(w.from, w.to) << "network " << n.index << " wire " << w.id;
    for (int c = w.from; !w.vertical && c < w.to; ++c)
      EXPECT_EQ(cells.count({w.row, c}), 0u) << "network " << n.index << ": wire " << w.id << " runs through ("
                                            << w.row << ", " << c << ")";
    EXPECT_LE(w.to, w.vertical ? n.rows - 1 : n.cols);
  }
}

}  // namespace test
}  // namespace ladder
}  // namespace plc_cell
