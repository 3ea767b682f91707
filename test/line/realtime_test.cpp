// A line in real time (docs/lines.md, "In real time"): each cell on its own scan thread, or
// the cells on shared scan threads, the wires carried after each scan. Nothing here asserts
// on speed: each wait is bounded and, past its bound, fails naming what it waited for.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "line_fixture.h"

namespace plc_cell {
namespace testing {
namespace {

// a copies X20 to Y0; b copies its X20 (a.Y0, 5 ms late) to Y0; c inverts b.Y0 into its R7.
LineFolder chain(const std::string& name) {
  return LineFolder(name, {{"copy.il", "ORG X20\nOUT Y0\nEND\n"},
                           {"c.il", "ORG NOT X20\nOUT Y0\nORG M1925\nMOV S=WX16 D=R7\nEND\n"},
                           {"a.yaml", cell_yaml("a", "copy.il")},
                           {"b.yaml", cell_yaml("b", "copy.il", "0.002")},
                           {"c.yaml", cell_yaml("c", "c.il")},
                           {"l.line.yaml", "cells: {a: a.yaml, b: b.yaml, c: c.yaml}\nwires:\n"
                                           "  - {from: a.Y0, to: b.X20, delay: 5ms}\n"
                                           "  - {from: b.Y0, to: c.X20, invert: true}\n"}});
}

// Polls until pred holds, at most 5 s; false past it.
template <class F>
bool within_5s(F pred) {
  for (int i = 0; i < 5000; ++i) {
    if (pred()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return pred();
}

void carries_a_change_down_the_chain(unsigned shared_threads) {
  LineFolder f = chain("rt" + std::to_string(shared_threads));
  line::LineOptions o;
  o.purpose = Cell::Purpose::Serve;
  line::Line l(f.path("l.line.yaml"), o);
  // Each cell's scans reported on its own thread, with instants that grow.
  std::atomic<uint64_t> reported[3] = {0, 0, 0};
  std::atomic<bool> backwards{false};
  std::atomic<uint64_t> last[3] = {0, 0, 0};
  l.after_scan([&](size_t i, uint64_t t) {
    if (reported[i]++ && t <= last[i]) backwards = true;
    last[i] = t;
  });
  l.start_real_time(shared_threads);
  // b.X20 OFF through the inverted wire: c's X20 ON, its R7 (WX16) shows bit 4 (X20).
  ASSERT_TRUE(within_5s([&] { return value(l, 2, "R7") == 16; })) << "c.R7 never read 16 (c.X20 ON)";
  l.cell(0)->plc().set_input(20, true);
  ASSERT_TRUE(within_5s([&] { return value(l, 1, "Y0") == 1; })) << "b.Y0 never turned ON after a.X20";
  ASSERT_TRUE(within_5s([&] { return value(l, 2, "R7") == 0; })) << "c.X20 never turned OFF after b.Y0";
  l.cell(0)->plc().set_input(20, false);
  ASSERT_TRUE(within_5s([&] { return value(l, 2, "R7") == 16; })) << "c.X20 never came back ON";
  ASSERT_TRUE(within_5s([&] { return reported[0] > 10 && reported[1] > 10 && reported[2] > 10; }))
      << "after_scan not called for every cell";
  l.stop();
  EXPECT_FALSE(backwards) << "a cell's scan instants went backwards";
  EXPECT_EQ(l.fault(), "");
}

TEST(RealTime, EachCellOnItsOwnThread) { carries_a_change_down_the_chain(0); }
TEST(RealTime, CellsOnSharedScanThreads) { carries_a_change_down_the_chain(1); }

}  // namespace
}  // namespace testing
}  // namespace plc_cell
