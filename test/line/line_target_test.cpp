// The line as one scenario target (docs/lines.md, "Tests across cells"): qualified names,
// the line's tick as the runner's scan, a scenario's set taking a wired input from its wire
// and simulate giving it back.
#include <gtest/gtest.h>

#include "line_fixture.h"
#include "plc_cell/line/line_target.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/scenario_file.h"

namespace plc_cell {
namespace testing {
namespace {

// a copies X20 to Y0 (scan 1 ms); b (scan 2 ms) copies X20 and X3 to Y0 and Y1. a.Y0 drives
// b.X20 (scanned) and b.X3 (exact edges), 5 ms late.
LineFolder copier(const std::string& name) {
  return LineFolder(name, {{"a.il", "ORG X20\nOUT Y0\nEND\n"},
                           {"b.il", "ORG X20\nOUT Y0\nORG X3\nOUT Y1\nEND\n"},
                           {"a.yaml", cell_yaml("a", "a.il", "0.001", "signals: {go: X20, out: Y0}\n")},
                           {"b.yaml", cell_yaml("b", "b.il", "0.002", "signals: {seen: Y0}\n")},
                           {"l.line.yaml", "cells: {a: a.yaml, b: b.yaml}\nwires:\n"
                                           "  - {from: a.out, to: b.X20, delay: 5ms}\n"
                                           "  - {from: a.out, to: b.X3, delay: 5ms}\n"}});
}

scenario::CaseResult run(const LineFolder& f, const std::string& steps) {
  const scenario::Scenario sc = scenario::parse_scenario(
      "line: l.line.yaml\ncases:\n  - name: c\n    steps:\n" + steps, f.dir() + "/s.scenario.yaml");
  line::LineTarget t(sc.line);
  const auto errors = scenario::check_case(sc.cases.at(0), t);
  if (!errors.empty()) {
    scenario::CaseResult r;
    r.failure = errors[0].to_string();
    return r;
  }
  return scenario::run_case(sc.cases.at(0), t);
}

TEST(LineTarget, TheRunnersScansAreTheLinesInstants) {
  LineFolder f = copier("instants");
  line::LineTarget t(f.path("l.line.yaml"));
  EXPECT_EQ(t.period_us(), 1000u);  // gcd(1 ms, 2 ms)
  // a.go at 10 ms: a.Y0 at 10 ms, b's inputs at 15 ms, b's first scan then is at 16 ms.
  const auto r = run(f, "      - at: 10ms\n        set: {a.go: on}\n"
                        "      - expect_sequence:\n"
                        "          - {that: a.out, between: [1ms, 1ms]}\n"
                        "          - {that: b.seen and b.Y1, between: [5ms, 5ms]}\n"
                        "        timeout: 20ms\n");
  EXPECT_TRUE(r.passed) << r.failure << "\n" << r.details;
}

TEST(LineTarget, ASetTakesAWiredInputFromItsWireAndSimulateGivesItBack) {
  LineFolder f = copier("take");
  // a.go stays OFF: the wire holds b's inputs OFF. The scenario sets them ON; then a's ON
  // output reaches them no more (a set holds); simulate gives them back to the wire, which
  // plays a.Y0's value (OFF again by then).
  const auto r = run(f, "      - set: {b.X20: on, b.X3: on}\n"
                        "      - expect: b.seen and b.Y1\n        within: 2ms\n"
                        "      - at: 10ms\n        set: {a.go: on}\n"
                        "      - at: 30ms\n        set: {a.go: off}\n"
                        "      - expect: b.seen and b.Y1\n        stays: 20ms\n"
                        "      - simulate: [b.X20, b.X3]\n"
                        "      - expect: not b.seen and not b.Y1\n        within: 2ms\n");
  EXPECT_TRUE(r.passed) << r.failure << "\n" << r.details;
}

TEST(LineTarget, EveryNameStartsWithItsCell) {
  LineFolder f = copier("names");
  line::LineTarget t(f.path("l.line.yaml"));
  EXPECT_EQ(t.check(scenario::parse_probe("X20"), false),
            "'X20': a line's names start with their cell: CELL.X20 (cells: a, b)");
  EXPECT_EQ(t.check(scenario::parse_probe("c.X20", scenario::Naming::Line), false),
            "'c.X20': no cell 'c' in the line (a, b)");
  EXPECT_EQ(t.check(scenario::parse_probe("a.nothing", scenario::Naming::Line), false),
            "a: 'nothing' is neither a signal of cell a nor an address ('nothing': unknown prefix (expected X, Y, M, S, "
            "T, C, RT, RC, R, D, F, a W/DW view such as WX8 or DWM0, or a 32-bit register such as DR0, DD0, DF0, DRT0, "
            "DRC200))");
  EXPECT_EQ(t.check(scenario::parse_probe("b.counter.x", scenario::Naming::Line), false),
            "b: no counter named 'x' in the cell's counters");
  EXPECT_EQ(t.label(scenario::parse_probe("a.out", scenario::Naming::Line)), "a.out (Y0)");
  EXPECT_EQ(t.label(scenario::parse_probe("a.Y0", scenario::Naming::Line)), "a.out (Y0)");
  EXPECT_EQ(t.label(scenario::parse_probe("b.R3", scenario::Naming::Line)), "b.R3");
}

TEST(LineTarget, AFaultNamesItsCell) {
  // b's endless backward jump trips the scan's loop budget once X0 is ON.
  LineFolder f("fault", {{"ok.il", "ORG X20\nOUT Y0\nEND\n"},
                         {"bad.il", "LBL L1\nORG X0\nJMP L1\nEND\n"},
                         {"a.yaml", cell_yaml("a", "ok.il")},
                         {"b.yaml", cell_yaml("b", "bad.il")},
                         {"l.line.yaml", "cells: {a: a.yaml, b: b.yaml}\n"}});
  line::LineTarget t(f.path("l.line.yaml"));
  t.scan(0);
  EXPECT_EQ(t.fault(), "");
  t.set(scenario::parse_probe("b.X0", scenario::Naming::Line), scenario::Value{1, false, "", "on"});
  t.scan(1000);
  EXPECT_EQ(t.fault(), "b: " + f.path("bad.il") + ":3: watchdog: more than 1000000 backward jumps in one scan");
}

}  // namespace
}  // namespace testing
}  // namespace plc_cell
