// A line built in parts (docs/lines.md, "A line over several processes"): each part builds
// its own cells, a wire with one end elsewhere is carried by someone else, and the run is
// the same as the whole line's in one process. And the order of the cells at one instant
// decides nothing a cell sees.
#include <gtest/gtest.h>

#include "line_fixture.h"

namespace plc_cell {
namespace testing {
namespace {

// Three cells in a ring with delays and an inversion: a counts the scans its X20 is ON in
// D0; b follows a.Y0 = X20 of a toggled by its own timer; c inverts b. Every cell's memory
// after 200 ms is the run's fingerprint.
std::map<std::string, std::string> ring(const std::string& order) {
  std::string cells;
  for (char c : order) cells += std::string("  ") + c + ": " + c + ".yaml\n";
  return {{"a.il", "ORG T0\nOUT M0\nORG NOT M0\nTMR T0 3\nORG T0\nFUN 15P INC D=D0\nORG X20\nOUT Y0\nORG M1925\nMOV S=D0 D=R0\nEND\n"},
          {"b.il", "ORG X20\nOUT Y0\nORG X21\nFUN 15P INC D=D1\nEND\n"},
          {"c.il", "ORG NOT X20\nOUT Y0\nEND\n"},
          {"a.yaml", cell_yaml("a", "a.il", "0.001")},
          {"b.yaml", cell_yaml("b", "b.il", "0.002")},
          {"c.yaml", cell_yaml("c", "c.il", "0.003")},
          {"l.line.yaml", "cells:\n" + cells +
                              "wires:\n"
                              "  - {from: a.M0, to: b.X20, delay: 7ms}\n"
                              "  - {from: b.Y0, to: c.X20}\n"
                              "  - {from: c.Y0, to: a.X20, delay: 1.5ms, invert: true}\n"
                              "  - {from: a.R0, to: b.R5, delay: 2ms}\n"
                              "  - {from: c.Y0, to: b.X21, part: {travel: 4ms, length: 1ms}}\n"}};
}

// Each named cell's memory (Y, M, R, D of interest) after the run, as text.
std::string memory(line::Line& l, const std::vector<std::string>& cells) {
  std::string s;
  for (const auto& name : cells) {
    const int i = l.find(name);
    s += name + ":";
    for (const char* a : {"X20", "X21", "Y0", "M0", "R0", "R5", "D0", "D1"}) s += " " + std::to_string(value(l, size_t(i), a));
    s += "\n";
  }
  return s;
}

std::string whole(const std::string& order, uint64_t until_us) {
  LineFolder f("order_" + order, ring(order));
  line::Line l(f.path("l.line.yaml"));
  l.run();
  for (uint64_t t = 0; t <= until_us; t += l.tick_us()) l.scan_at(t);
  return memory(l, {"a", "b", "c"});
}

TEST(Split, TheOrderOfTheCellsDecidesNothing) {
  const std::string abc = whole("abc", 200000);
  for (const std::string order : {"acb", "bac", "bca", "cab", "cba"}) EXPECT_EQ(whole(order, 200000), abc) << order;
  // A lively run: a's 30 ms timer restarts the scan after it ends (T0 ON at 30, 62, ...,
  // 190 ms: D0 = 6), b's R5 has a's R0 2 ms late, b counts c's rising outputs as parts.
  EXPECT_EQ(abc.substr(0, abc.find('\n')), "a: 0 0 0 0 6 0 6 0") << abc;
  EXPECT_NE(abc.find("b: 0 0 0 0 0 6 0 "), std::string::npos) << abc;
  EXPECT_EQ(abc.find("b: 0 0 0 0 0 6 0 0"), std::string::npos) << abc;
}

TEST(Split, TwoProcessesHalvesRunAsTheWholeLine) {
  LineFolder f("split", ring("abc"));
  line::LineOptions here_a, here_bc;
  here_a.here = {"a"};
  here_bc.here = {"b", "c"};
  line::Line left(f.path("l.line.yaml"), here_a), right(f.path("l.line.yaml"), here_bc);
  EXPECT_EQ(left.cell(0) != nullptr, true);
  EXPECT_EQ(left.cell(1), nullptr);
  EXPECT_EQ(right.cell(0), nullptr);
  // The carrier between the two: each sample of a half wire, delivered at its instant (both
  // halves share one virtual clock here).
  left.on_remote_sample([&](size_t w, uint64_t t, uint32_t v) { right.receive(w, t, v); });
  right.on_remote_sample([&](size_t w, uint64_t t, uint32_t v) { left.receive(w, t, v); });
  left.run();
  right.run();
  // Each half's own grid (1 ms and gcd(2, 3) = 1 ms): both scan at every instant of the whole.
  EXPECT_EQ(left.tick_us(), 1000u);
  for (uint64_t t = 0; t <= 200000; t += 1000) {
    left.scan_at(t);
    right.scan_at(t);
  }
  EXPECT_EQ(memory(left, {"a"}) + memory(right, {"b", "c"}), whole("abc", 200000));
}

TEST(Split, AWireWithNoSinkHereIsRefusedByReceive) {
  LineFolder f("split_refuse", ring("abc"));
  line::LineOptions here_a;
  here_a.here = {"a"};
  line::Line left(f.path("l.line.yaml"), here_a);
  left.run();
  EXPECT_THROW(left.receive(0, 1), Error);  // a.M0 -> b.X20: its sink is b, not here
}

}  // namespace
}  // namespace testing
}  // namespace plc_cell
