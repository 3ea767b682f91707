// When a wire delivers (docs/lines.md, "When a wire delivers"): the source's value sampled
// at the end of its scan at t reaches the sink at t + delay, seen by the sink's first scan
// at or after that instant; a zero delay by the sink's first scan after t. Every expected
// instant below is worked out by hand from that rule.
#include <gtest/gtest.h>

#include "line_fixture.h"

namespace plc_cell {
namespace testing {
namespace {

constexpr const char* kCopy = "ORG X20\nOUT Y0\nEND\n";  // Y0 follows X20

// a copies X20 to Y0; b copies its X20 (wired from a.Y0) to Y0. The cells in `order`.
LineFolder two_cells(const std::string& name, const std::string& wire, const std::string& order = "ab",
                     const std::string& period_a = "0.001", const std::string& period_b = "0.001") {
  const std::string a = "  a: a.yaml\n", b = "  b: b.yaml\n";
  return LineFolder(name, {{"copy.il", kCopy},
                           {"a.yaml", cell_yaml("a", "copy.il", period_a)},
                           {"b.yaml", cell_yaml("b", "copy.il", period_b)},
                           {"l.line.yaml", "cells:\n" + (order == "ab" ? a + b : b + a) + "wires:\n  - " + wire + "\n"}});
}

// a's X20 goes ON after the scan at on_us; the first instant (on the tick grid, up to
// 100 ms) at which b's Y0 reads ON, or UINT64_MAX.
uint64_t first_on(line::Line& l, uint64_t on_us) {
  l.run();
  const size_t a = size_t(l.find("a")), b = size_t(l.find("b"));
  for (uint64_t t = 0; t <= 100000; t += l.tick_us()) {
    l.scan_at(t);
    if (value(l, b, "Y0")) return t;
    if (t == on_us) l.cell(a)->plc().set_input(20, true);
  }
  return UINT64_MAX;
}

TEST(Delivery, ADelayedWireIsSeenByTheFirstScanAtItsInstant) {
  // a scans X20 ON at 5 ms: Y0 ON at the end of that scan; + 10 ms = 15 ms, a scan of b.
  LineFolder f = two_cells("delay10", "{from: a.Y0, to: b.X20, delay: 10ms}");
  line::Line l(f.path("l.line.yaml"));
  EXPECT_EQ(first_on(l, 4000), 15000u);
}

TEST(Delivery, ADelayBetweenScansIsSeenByTheNextScan) {
  // Sampled at 5 ms, delivered at 7.5 ms: b's scans are at 7 and 8 ms, so 8 ms.
  LineFolder f = two_cells("delay2_5", "{from: a.Y0, to: b.X20, delay: 2.5ms}");
  line::Line l(f.path("l.line.yaml"));
  EXPECT_EQ(first_on(l, 4000), 8000u);
}

TEST(Delivery, AZeroDelayIsSeenByTheSinksNextScanWhateverTheOrder) {
  // Sampled at 5 ms (end of a's scan), delivered just after: b's scan at 5 ms read its
  // inputs at 5 ms, before; its scan at 6 ms sees it, whether b scans before or after a.
  for (const std::string order : {"ab", "ba"}) {
    LineFolder f = two_cells("zero_" + order, "{from: a.Y0, to: b.X20}", order);
    line::Line l(f.path("l.line.yaml"));
    EXPECT_EQ(first_on(l, 4000), 6000u) << "order " << order;
  }
}

TEST(Delivery, AnInvertedWireStartsOnAndFollowsItsSourceInverted) {
  LineFolder f = two_cells("invert", "{from: a.Y0, to: b.X20, delay: 1ms, invert: true}");
  line::Line l(f.path("l.line.yaml"));
  l.run();
  l.scan_at(0);
  EXPECT_EQ(value(l, 1, "Y0"), 1u);  // a.Y0 OFF before the first scan: b's X20 ON from the start
  l.cell(0)->plc().set_input(20, true);
  l.scan_at(1000);                    // a.Y0 ON at 1 ms: b's X20 OFF at 2 ms
  l.scan_at(2000);
  EXPECT_EQ(value(l, 1, "Y0"), 0u);
}

TEST(Delivery, CellsOfDifferentPeriodsShareOneClock) {
  // a scans every 2 ms, b every 3 ms: the line's instants are every 1 ms (their gcd), a at
  // 0, 2, 4, ... and b at 0, 3, 6, ... a sees X20 at 6 ms (set after its 4 ms scan), Y0 ON
  // then; zero delay: b's first scan after 6 ms is at 9 ms.
  LineFolder f = two_cells("periods", "{from: a.Y0, to: b.X20}", "ab", "0.002", "0.003");
  line::Line l(f.path("l.line.yaml"));
  EXPECT_EQ(l.tick_us(), 1000u);
  EXPECT_EQ(first_on(l, 4000), 9000u);
  EXPECT_EQ(l.cell(0)->plc().locked([](ScanEngine& e, Memory&) { return e.stats().scans; }), 5u);  // 0, 2, 4, 6, 8
  EXPECT_EQ(l.cell(1)->plc().locked([](ScanEngine& e, Memory&) { return e.stats().scans; }), 4u);  // 0, 3, 6, 9
}

TEST(Delivery, AZeroDelayCycleTakesOneScanPerCrossing) {
  // a: Y0 = NOT X20; b: Y0 = X20; a.Y0 -> b.X20 and b.Y0 -> a.X20, both with no delay.
  // No algebraic loop: each crossing waits for the next scan. a sees b's Y0 of the scan
  // before, which saw a's Y0 of the scan before that: a.Y0(t) = NOT a.Y0(t - 2 scans),
  // from a.Y0 = 1 at 0 and 1 ms (X20 starts OFF): 1 1 0 0 1 1 0 0 ... (period 4 ms).
  LineFolder f("cycle", {{"not.il", "ORG NOT X20\nOUT Y0\nEND\n"},
                         {"copy.il", kCopy},
                         {"a.yaml", cell_yaml("a", "not.il")},
                         {"b.yaml", cell_yaml("b", "copy.il")},
                         {"l.line.yaml", "cells: {a: a.yaml, b: b.yaml}\n"
                                         "wires:\n  - {from: a.Y0, to: b.X20}\n  - {from: b.Y0, to: a.X20}\n"}});
  line::Line l(f.path("l.line.yaml"));
  l.run();
  std::string a, b;
  for (uint64_t t = 0; t < 10000; t += 1000) {
    l.scan_at(t);
    a += char('0' + value(l, 0, "Y0"));
    b += char('0' + value(l, 1, "Y0"));
  }
  EXPECT_EQ(a, "1100110011");
  EXPECT_EQ(b, "0110011001");  // a's, one scan later
}

TEST(Delivery, ARegisterTravelsWithItsWholeValue) {
  // a counts its scans in D0; b's R10 receives it 2 ms late, b copies it to D1.
  LineFolder f("register", {{"count.il", "ORG M1925\nFUN 11 Sa=D0 Sb=1 D=D0\nEND\n"},
                            {"copy_r.il", "ORG M1925\nMOV S=R10 D=D1\nEND\n"},
                            {"a.yaml", cell_yaml("a", "count.il")},
                            {"b.yaml", cell_yaml("b", "copy_r.il")},
                            {"l.line.yaml", "cells: {a: a.yaml, b: b.yaml}\nwires:\n  - {from: a.D0, to: b.R10, delay: 2ms}\n"}});
  line::Line l(f.path("l.line.yaml"));
  l.run();
  for (uint64_t t = 0; t <= 10000; t += 1000) l.scan_at(t);
  // a's D0 is 11 after its scan at 10 ms (1 at 0 ms); b's scan at 10 ms sees what a had at
  // 8 ms: 9.
  EXPECT_EQ(value(l, 0, "D0"), 11u);
  EXPECT_EQ(value(l, 1, "D1"), 9u);
}

}  // namespace
}  // namespace testing
}  // namespace plc_cell
