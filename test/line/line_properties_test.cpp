// A scenario file's properties watched over a line's run (docs/monitor.md, "Properties"):
// evaluated at every instant of the line once every cell due at it has scanned; a violation
// counts once it lasted longer than its grace, begins at the first instant violated and
// ends at the first instant the property holds again. Every figure below follows from that
// rule and the 1 ms scans.
#include <gtest/gtest.h>

#include <random>

#include "line_fixture.h"
#include "plc_cell/line/line_properties.h"

namespace plc_cell {
namespace testing {
namespace {

constexpr const char* kCopy = "ORG X20\nOUT Y0\nEND\n";  // Y0 follows X20

// a and b copy their X20 to Y0, every period; a wire neither test drives (a.Y1 -> b.X21).
LineFolder copies(const std::string& name, const std::string& order = "ab", const std::string& period_b = "0.001") {
  const std::string a = "  a: a.yaml\n", b = "  b: b.yaml\n";
  return LineFolder(name, {{"copy.il", kCopy},
                           {"a.yaml", cell_yaml("a", "copy.il")},
                           {"b.yaml", cell_yaml("b", "copy.il", period_b)},
                           {"l.line.yaml", "cells:\n" + (order == "ab" ? a + b : b + a) +
                                               "wires:\n  - {from: a.Y1, to: b.X21}\n"}});
}

scenario::Property property(bool never, const std::string& text, uint64_t within_us = 0) {
  scenario::Property p = scenario::parse_property(never, text, scenario::Naming::Line);
  p.within_us = within_us;
  p.file = "watch.scenario.yaml";
  p.line = 7;
  return p;
}

std::shared_ptr<scenario::PropertyWatcher> watch(line::Line& l, std::vector<scenario::Property> ps,
                                                 bool history = false) {
  auto w = std::make_shared<scenario::PropertyWatcher>(
      std::move(ps),
      [&l](const scenario::Probe& p) {
        const int i = l.find(p.cell);
        if (i < 0) throw Error("no cell " + p.cell);
        return scenario::WatchedAddress{size_t(i), l.cell(size_t(i))->config().resolve(p.name)};
      },
      "watch.scenario.yaml", "test", history);
  line::watch_properties(l, w);
  return w;
}

// Scans l at every ms from *t up to (not including) end_ms, X20 of a and b as given.
void run_until(line::Line& l, uint64_t* t, uint64_t end_ms, bool a_on, bool b_on) {
  l.cell(size_t(l.find("a")))->plc().set_input(20, a_on);
  l.cell(size_t(l.find("b")))->plc().set_input(20, b_on);
  for (; *t < end_ms * 1000; *t += 1000) l.scan_at(*t);
}

TEST(LineProperties, AViolationOfNScansIsReportedAsNScans) {
  // Random lengths from a fixed seed: each violation, 1 to 40 scans, seen as exactly that.
  std::mt19937 rng(7);
  for (int round = 0; round < 20; ++round) {
    LineFolder f = copies("n_scans");
    line::Line l(f.path("l.line.yaml"));
    auto w = watch(l, {property(true, "a.Y0 and b.Y0")});
    l.run();
    uint64_t t = 0;
    const uint64_t start = 1 + rng() % 30, n = 1 + rng() % 40;
    run_until(l, &t, start, true, false);
    EXPECT_EQ(w->report().properties[0].violations, 0u);
    // b's X20 on before the scan at `start` ms: both Y0 ON from that scan on, for n scans.
    run_until(l, &t, start + n, true, true);
    run_until(l, &t, start + n + 5, true, false);
    const auto r = w->report();
    ASSERT_EQ(r.properties.size(), 1u);
    const auto& p = r.properties[0];
    EXPECT_EQ(p.violations, 1u) << "round " << round;
    EXPECT_FALSE(p.violated);
    EXPECT_FALSE(p.last_ongoing);
    EXPECT_EQ(p.last_begin_us, start * 1000) << "round " << round;
    EXPECT_EQ(p.last_duration_us, n * 1000) << "round " << round << ": " << n << " scans";
    ASSERT_EQ(p.last_values.size(), 2u);
    EXPECT_EQ(p.last_values[0].name, "a.Y0");
    EXPECT_EQ(p.last_values[0].value, "ON");
    EXPECT_EQ(p.last_values[1].value, "ON");
    EXPECT_EQ(p.text, "never: a.Y0 and b.Y0");
    EXPECT_EQ(p.where, "watch.scenario.yaml:7");
  }
}

TEST(LineProperties, AViolationGoingOnIsViolatedSinceItsFirstInstant) {
  LineFolder f = copies("ongoing");
  line::Line l(f.path("l.line.yaml"));
  auto w = watch(l, {property(false, "a.Y0 -> not b.Y0")});
  l.run();
  uint64_t t = 0;
  run_until(l, &t, 10, true, false);
  run_until(l, &t, 14, true, true);  // violated at 10..13 ms; the instant 13 ms is evaluated at 14 ms
  l.scan_at(t);
  const auto p = w->report().properties[0];
  EXPECT_TRUE(p.violated);
  EXPECT_EQ(p.since_us, 10000u);
  EXPECT_EQ(p.violations, 1u);
  EXPECT_TRUE(p.last_ongoing);
  EXPECT_EQ(p.last_duration_us, 3000u);  // 10 ms to the last instant evaluated, 13 ms
  EXPECT_EQ(w->report().t_us, 13000u);
}

TEST(LineProperties, AViolationWithinItsGraceDoesNotCount) {
  LineFolder f = copies("grace");
  line::Line l(f.path("l.line.yaml"));
  auto w = watch(l, {property(true, "a.Y0 and b.Y0", 2000)});
  l.run();
  uint64_t t = 0;
  run_until(l, &t, 10, true, false);
  run_until(l, &t, 13, true, true);  // 3 scans: 10, 11, 12 ms, the last 2 ms after the first: within
  run_until(l, &t, 20, true, false);
  EXPECT_EQ(w->report().properties[0].violations, 0u);
  run_until(l, &t, 24, true, true);  // 4 scans: at 23 ms it has lasted 3 ms > 2 ms
  run_until(l, &t, 30, true, false);
  const auto p = w->report().properties[0];
  EXPECT_EQ(p.violations, 1u);
  EXPECT_EQ(p.last_begin_us, 20000u);
  EXPECT_EQ(p.last_duration_us, 4000u);
}

TEST(LineProperties, AnInstantIsSeenOnceEveryCellScannedAtIt) {
  // Before the scan at 10 ms a goes ON and b OFF: after a's scan at 10 ms and before b's,
  // both read ON, but no instant of the line has both ON. Either order of the cells.
  for (const std::string order : {"ab", "ba"}) {
    LineFolder f = copies("instant_" + order, order);
    line::Line l(f.path("l.line.yaml"));
    auto w = watch(l, {property(true, "a.Y0 and b.Y0")});
    l.run();
    uint64_t t = 0;
    run_until(l, &t, 10, false, true);
    run_until(l, &t, 20, true, false);
    EXPECT_EQ(w->report().properties[0].violations, 0u) << "order " << order;
  }
}

TEST(LineProperties, ACellOfLongerPeriodKeepsItsValueBetweenItsScans) {
  // b scans every 2 ms (even ms); b's X20 on from 10 ms to 15 ms: its Y0 ON at its scans
  // at 10, 12 and 14 ms, OFF at 16 ms. a ON throughout: violated from 10 ms to 16 ms.
  LineFolder f = copies("periods", "ab", "0.002");
  line::Line l(f.path("l.line.yaml"));
  auto w = watch(l, {property(true, "a.Y0 and b.Y0")});
  l.run();
  uint64_t t = 0;
  run_until(l, &t, 10, true, false);
  run_until(l, &t, 15, true, true);
  run_until(l, &t, 25, true, false);
  const auto p = w->report().properties[0];
  EXPECT_EQ(p.violations, 1u);
  EXPECT_EQ(p.last_begin_us, 10000u);
  EXPECT_EQ(p.last_duration_us, 6000u);
}

TEST(LineProperties, AHistoryAnswersAtAnyInstantOfTheRun) {
  LineFolder f = copies("history");
  line::Line l(f.path("l.line.yaml"));
  auto w = watch(l, {property(true, "a.Y0 and b.Y0")}, true);
  l.run();
  uint64_t t = 0;
  run_until(l, &t, 10, true, false);
  run_until(l, &t, 13, true, true);  // 10..12 ms
  run_until(l, &t, 20, true, false);
  run_until(l, &t, 25, true, true);  // 20..24 ms
  run_until(l, &t, 30, true, false);
  w->flush();
  EXPECT_EQ(w->report_at(9000).properties[0].violations, 0u);
  auto p = w->report_at(11000).properties[0];  // within the first: going on for 1 ms
  EXPECT_EQ(p.violations, 1u);
  EXPECT_TRUE(p.violated);
  EXPECT_EQ(p.last_duration_us, 1000u);
  p = w->report_at(15000).properties[0];
  EXPECT_FALSE(p.violated);
  EXPECT_EQ(p.last_duration_us, 3000u);
  p = w->report_at(29000).properties[0];
  EXPECT_EQ(p.violations, 2u);
  EXPECT_EQ(p.last_begin_us, 20000u);
  EXPECT_EQ(p.last_duration_us, 5000u);
}

TEST(LineProperties, ANameNoCellHasIsRefusedAtItsPropertysLine) {
  LineFolder f = copies("unknown");
  line::Line l(f.path("l.line.yaml"));
  try {
    watch(l, {property(true, "a.Y0"), property(true, "c.Y0 and a.nothing_here")});
    FAIL() << "accepted";
  } catch (const SourceError& e) {
    ASSERT_EQ(e.diagnostics().size(), 2u);  // each name, each at its property
    EXPECT_EQ(e.diagnostics()[0].where.file, "watch.scenario.yaml");
    EXPECT_EQ(e.diagnostics()[0].where.line, 7);
    EXPECT_NE(e.diagnostics()[0].message.find("no cell c"), std::string::npos) << e.what();
    EXPECT_NE(e.diagnostics()[1].message.find("nothing_here"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace testing
}  // namespace plc_cell
