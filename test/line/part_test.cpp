// Travelling parts and exact instants (docs/lines.md, "A part that travels", "Inputs that
// see exact instants"). The instants expected below are worked out by hand.
#include <gtest/gtest.h>

#include "line_fixture.h"
#include "plc_cell/line/line_target.h"
#include "plc_cell/scenario/probe.h"

namespace plc_cell {
namespace testing {
namespace {

scenario::Reading read(line::LineTarget& t, const std::string& name) {
  return t.read(scenario::parse_probe(name, scenario::Naming::Line));
}

// a's Y0 follows X20, which the test sets ON for the scans in `on` (ms); b receives
// a.Y0 as parts on X20 (scanned) and sees them in its Y0.
std::string sensor(const std::string& name, const std::string& part, const std::vector<int>& on, int until_ms) {
  LineFolder f(name, {{"copy.il", "ORG X20\nOUT Y0\nEND\n"},
                      {"a.yaml", cell_yaml("a", "copy.il")},
                      {"b.yaml", cell_yaml("b", "copy.il")},
                      {"l.line.yaml", "cells: {a: a.yaml, b: b.yaml}\nwires:\n  - {from: a.Y0, to: b.X20, part: " + part + "}\n"}});
  line::Line l(f.path("l.line.yaml"));
  l.run();
  std::string seen;
  for (int ms = 0; ms <= until_ms; ++ms) {
    l.scan_at(uint64_t(ms) * 1000);
    seen += char('0' + value(l, 1, "Y0"));
    const bool next_on = std::find(on.begin(), on.end(), ms + 1) != on.end();
    l.cell(0)->plc().set_input(20, next_on);  // seen by a's next scan
  }
  return seen;
}

TEST(Part, EachRisingEdgeIsAPartThatCoversTheSensorAfterItsTravel) {
  // Rising edges at 1 and 20 ms (a.Y0 ON at scans 1-3 and 20): parts over [6, 8) and
  // [25, 27) ms; however long the source stays ON, a part covers the sensor its length.
  const std::string s = sensor("travel", "{travel: 5ms, length: 2ms}", {1, 2, 3, 20}, 30);
  EXPECT_EQ(s, "0000001100000000000000000110000");
  //            0         1         2         3 (ms)
}

TEST(Part, SeveralPartsInFlightAndOverlappingOnesCoverTheSensorTogether) {
  // Rising edges at 1, 3 and 20 ms, 3 ms long parts after 5 ms: [6, 9), [8, 11), [25, 28).
  // The first two are both travelling at 3 ms and overlap at the sensor: it stays covered
  // from 6 to 11 ms.
  const std::string s = sensor("overlap", "{travel: 5ms, length: 3ms}", {1, 3, 20}, 30);
  EXPECT_EQ(s, "0000001111100000000000000111000");
}

TEST(Part, AnInputWithExactEdgesSeesAPartBetweenTwoScans) {
  // A 0.3 ms part 2.5 ms after a.Y0 rises: at 1 ms -> [3.5, 3.8) ms, at 6 ms -> [8.5, 8.8)
  // ms, both between b's 1 ms scans. The same source drives three inputs of b:
  //   X0, an input with exact edges (HSC0 counts it, its pulses measured): 2 counts, and at
  //      the second part's rise a cycle of exactly 5000 us with 300 us ON;
  //   X20, scanned: never ON at a scan (M0 never set);
  //   X21, a capture input: each part latched for the next scan (M1 set).
  const std::string part = "part: {travel: 2.5ms, length: 0.3ms}";
  LineFolder f("exact", {{"copy.il", "ORG X20\nOUT Y0\nEND\n"},
                         {"b.il", "ORG X20\nSET M0\nORG X21\nSET M1\nEND\n"},
                         {"a.yaml", cell_yaml("a", "copy.il")},
                         {"b.yaml", cell_yaml("b", "b.il", "0.001",
                                              "counters:\n  hsc0: {mode: MD0, name: parts}\n  capture: [X21]\n"
                                              "  pulse_measurement: {inputs: [X0]}\n")},
                         {"l.line.yaml", "cells: {a: a.yaml, b: b.yaml}\nwires:\n"
                                         "  - {from: a.Y0, to: b.X0, " + part + "}\n"
                                         "  - {from: a.Y0, to: b.X20, " + part + "}\n"
                                         "  - {from: a.Y0, to: b.X21, " + part + "}\n"}});
  line::LineTarget t(f.path("l.line.yaml"));
  for (uint64_t ms = 0; ms <= 10; ++ms) {
    t.scan(ms * 1000);
    t.line().cell(0)->plc().set_input(20, ms == 0 || ms == 5);  // a.Y0 ON at 1 and 6 ms
  }
  EXPECT_EQ(read(t, "b.counter.parts").number, 2);
  EXPECT_EQ(read(t, "b.pulse.X0.period").number, 5000);
  EXPECT_EQ(read(t, "b.pulse.X0.width").number, 300);
  EXPECT_EQ(read(t, "b.M0").number, 0);
  EXPECT_EQ(read(t, "b.M1").number, 1);
}

TEST(Part, AnExactInputFollowsAPlainWireAtTheDelaysInstant) {
  // a.Y0 ON at 1 ms and OFF at 3 ms, 0.25 ms later on b.X0: ON from 1.25 to 3.25 ms. With
  // the next pulse (ON at 5 ms -> 5.25 ms) the meter reads a 4000 us cycle, 2000 us ON:
  // both edges moved by the delay exactly, between b's scans.
  LineFolder f("exact_delay", {{"copy.il", "ORG X20\nOUT Y0\nEND\n"},
                               {"nop.il", "ORG M1925\nOUT M0\nEND\n"},
                               {"a.yaml", cell_yaml("a", "copy.il")},
                               {"b.yaml", cell_yaml("b", "nop.il", "0.001",
                                                    "counters:\n  hsc0: {mode: MD0}\n  pulse_measurement: {inputs: [X0]}\n")},
                               {"l.line.yaml", "cells: {a: a.yaml, b: b.yaml}\n"
                                               "wires:\n  - {from: a.Y0, to: b.X0, delay: 0.25ms}\n"}});
  line::LineTarget t(f.path("l.line.yaml"));
  for (uint64_t ms = 0; ms <= 6; ++ms) {
    t.scan(ms * 1000);
    t.line().cell(0)->plc().set_input(20, ms == 0 || ms == 1 || ms >= 4);
  }
  EXPECT_EQ(read(t, "b.pulse.X0.period").number, 4000);
  EXPECT_EQ(read(t, "b.pulse.X0.width").number, 2000);
}

}  // namespace
}  // namespace testing
}  // namespace plc_cell
