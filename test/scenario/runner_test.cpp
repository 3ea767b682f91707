// The runner's timeline and checks as docs/testing-your-cell.md defines them, on a small
// cell scanned every 1 ms. Expected times are computed by hand from the definitions.
#include <gtest/gtest.h>

#include "scenario_fixture.h"

using namespace plc_cell;
using namespace plc_cell::scenario;
using plc_cell::testing::ScenarioCell;

namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(ScenarioRunner, AnActionTakesEffectAtTheNextScan) {
  ScenarioCell cell("next_scan");
  // at: 100ms runs the scan at 100 ms; the set comes after it, so Y0 follows at 101 ms.
  const CaseResult r = cell.run(
      "      - at: 100ms\n"
      "        set: {start: on}\n"
      "      - expect: not motor\n"
      "      - after: 1ms\n"
      "        expect: motor\n");
  EXPECT_TRUE(r.passed) << r.failure << r.details;
  EXPECT_EQ(r.virtual_us, 101000u);
  EXPECT_EQ(r.scans, 102u);  // 0, 1, ..., 101 ms
}

TEST(ScenarioRunner, StaysFailsAtTheFirstScanWhereItIsFalse) {
  ScenarioCell cell("stays");
  // Set before the first scan, X1 is on from the scan at 0: T0 (0.5 s) is up at the scan
  // at 500 ms.
  const CaseResult ok = cell.run(
      "      - set: {hold: on}\n"
      "      - expect: not done\n"
      "        stays: 499ms\n");
  EXPECT_TRUE(ok.passed) << ok.failure << ok.details;
  const CaseResult bad = cell.run(
      "      - set: {hold: on}\n"
      "      - expect: not done\n"
      "        stays: 600ms\n");
  ASSERT_FALSE(bad.passed);
  EXPECT_TRUE(has(bad.failure, "s.yaml:6: expect not done to stay for 0.600 s: false at 0.500 s (0.500 s in)"))
      << bad.failure;
  EXPECT_EQ(bad.virtual_us, 500000u);
  EXPECT_TRUE(has(bad.details, "done (Y1):  initially OFF  0.500 s ON")) << bad.details;
}

TEST(ScenarioRunner, WithinAndBetweenBoundTheFirstScanThatHolds) {
  ScenarioCell cell("window");
  // done comes at the scan at 500 ms (see above).
  EXPECT_TRUE(cell.run("      - set: {hold: on}\n      - expect: done\n        within: 500ms\n").passed);
  const CaseResult late = cell.run("      - set: {hold: on}\n      - expect: done\n        within: 499ms\n");
  ASSERT_FALSE(late.passed);
  EXPECT_TRUE(has(late.failure, "expect done within 0.499 s: never held: done (Y1) is OFF")) << late.failure;
  EXPECT_EQ(late.virtual_us, 499000u);
  EXPECT_TRUE(cell.run("      - set: {hold: on}\n      - expect: done\n        between: [500ms, 501ms]\n").passed);
  const CaseResult early = cell.run("      - set: {hold: on}\n      - expect: done\n        between: [501ms, 600ms]\n");
  ASSERT_FALSE(early.passed);
  EXPECT_TRUE(has(early.failure, "held already at 0.500 s (0.500 s in, before the window)")) << early.failure;
}

TEST(ScenarioRunner, WaitUntilTimesOutSayingWhatIsStillFalse) {
  ScenarioCell cell("wait");
  const CaseResult ok = cell.run("      - set: {hold: on}\n      - wait_until: done\n        timeout: 1s\n");
  EXPECT_TRUE(ok.passed);
  EXPECT_EQ(ok.virtual_us, 500000u);  // the wait ends at the scan where it holds
  const CaseResult r = cell.run(
      "      - write: {R100: 7}\n"
      "      - wait_until: R101 == 7 and motor and R100 >= 0\n"
      "        timeout: 250ms\n");
  ASSERT_FALSE(r.passed);
  // Only what is still false is listed, with its value; R101 == 7 holds since the first scan.
  EXPECT_TRUE(has(r.failure, "wait_until R101 == 7 and motor and R100 >= 0: still false after 0.250 s: "
                             "motor (Y0) is OFF"))
      << r.failure;
  EXPECT_EQ(r.virtual_us, 250000u);
}

TEST(ScenarioRunner, SequenceEntriesAreChangesInOrderWithBounds) {
  ScenarioCell cell("sequence");
  const CaseResult ok = cell.run(
      "      - pulse: {start: 5ms}\n"
      "      - expect_sequence:\n"
      "          - {that: motor, within: 1ms}\n"
      "          - {that: not motor, between: [5ms, 5ms]}\n"
      "        timeout: 1s\n");
  EXPECT_TRUE(ok.passed) << ok.failure << ok.details;
  EXPECT_EQ(ok.virtual_us, 5000u);  // on at 0 ms (the pulse starts at the next scan), off at 5 ms
  // A level already true when the sequence starts is no change: it must go and come back.
  const CaseResult stale = cell.run(
      "      - set: {start: on}\n"
      "      - after: 1ms\n"
      "      - expect_sequence:\n"
      "          - motor\n"
      "        timeout: 100ms\n");
  ASSERT_FALSE(stale.passed);
  EXPECT_TRUE(has(stale.failure, "entry 1 (line 8) 'motor' did not happen within the sequence's 0.100 s")) << stale.failure;
  // Out of order: motor (Y0) never follows done.
  const CaseResult order = cell.run(
      "      - set: {hold: on}\n"
      "      - expect_sequence:\n"
      "          - done\n"
      "          - {that: motor, within: 1s}\n"
      "        timeout: 2s\n"
      "      - after: 0s\n");
  ASSERT_FALSE(order.passed);
  EXPECT_TRUE(has(order.failure, "entry 2 (line 8) 'motor' did not happen within 1.000 s of entry 1's match at 0.500 s"))
      << order.failure;
  const CaseResult early = cell.run(
      "      - pulse: {start: 5ms}\n"
      "      - expect_sequence:\n"
      "          - motor\n"
      "          - {that: not motor, between: [6ms, 10ms]}\n");
  ASSERT_FALSE(early.passed);
  EXPECT_TRUE(has(early.failure, "entry 2 (line 8) 'not motor' happened 0.005 s after entry 1's match, before the "
                                 "earliest 0.006 s"))
      << early.failure;
}

// Every way an entry can fail says why, with the values, in the headline itself
// (docs/testing-your-cell.md: "what was still false with its value").
TEST(ScenarioRunner, SequenceFailureHeadlinesSayWhyWithTheValues) {
  ScenarioCell cell("sequence_why");
  // Never true within the sequence's timeout: what is still false.
  const CaseResult never = cell.run(
      "      - expect_sequence:\n"
      "          - motor\n"
      "        timeout: 100ms\n");
  ASSERT_FALSE(never.passed);
  EXPECT_TRUE(has(never.failure, "expect_sequence: entry 1 (line 6) 'motor' did not happen within the sequence's "
                                 "0.100 s: motor (Y0) is OFF"))
      << never.failure;
  // True when the sequence starts and never false since: no change, and the value says so.
  const CaseResult stale = cell.run(
      "      - set: {start: on}\n"
      "      - after: 1ms\n"
      "      - expect_sequence:\n"
      "          - motor\n"
      "        timeout: 100ms\n");
  ASSERT_FALSE(stale.passed);
  EXPECT_TRUE(has(stale.failure, "entry 1 (line 8) 'motor' did not happen within the sequence's 0.100 s: already "
                                 "true when the sequence started, and never went false since: motor (Y0) is ON"))
      << stale.failure;
  // The same for a later entry, bounded from the previous match: done comes at 0.5 s.
  const CaseResult stale2 = cell.run(
      "      - set: {start: on, hold: on}\n"
      "      - after: 1ms\n"
      "      - expect_sequence:\n"
      "          - done\n"
      "          - {that: motor, within: 100ms}\n");
  ASSERT_FALSE(stale2.passed);
  EXPECT_TRUE(has(stale2.failure, "entry 2 (line 9) 'motor' did not happen within 0.100 s of entry 1's match at "
                                  "0.500 s: already true when the sequence started, before entry 1's match at "
                                  "0.500 s, and never went false since: motor (Y0) is ON"))
      << stale2.failure;
  EXPECT_EQ(stale2.virtual_us, 600000u);
  // Turned true after the start but before the previous entry matched: when, and the value.
  // The pulse turns motor on at the scan at 0, done comes at 0.5 s.
  const CaseResult early_rise = cell.run(
      "      - set: {hold: on}\n"
      "      - pulse: {start: 2s}\n"
      "      - expect_sequence:\n"
      "          - done\n"
      "          - {that: motor, within: 100ms}\n");
  ASSERT_FALSE(early_rise.passed);
  EXPECT_TRUE(has(early_rise.failure, "entry 2 (line 9) 'motor' did not happen within 0.100 s of entry 1's match "
                                      "at 0.500 s: became true at 0.000 s, before entry 1's match at 0.500 s, and "
                                      "never went false since: motor (Y0) is ON"))
      << early_rise.failure;
  // False at the end of its window: what is still false.
  const CaseResult late = cell.run(
      "      - set: {hold: on}\n"
      "      - expect_sequence:\n"
      "          - done\n"
      "          - {that: motor, within: 100ms}\n");
  ASSERT_FALSE(late.passed);
  EXPECT_TRUE(has(late.failure, "entry 2 (line 8) 'motor' did not happen within 0.100 s of entry 1's match at "
                                "0.500 s: motor (Y0) is OFF"))
      << late.failure;
  // Too early: when, the bound, and the values at that scan.
  const CaseResult early = cell.run(
      "      - pulse: {start: 5ms}\n"
      "      - expect_sequence:\n"
      "          - motor\n"
      "          - {that: not motor, between: [6ms, 10ms]}\n");
  ASSERT_FALSE(early.passed);
  EXPECT_TRUE(has(early.failure, "entry 2 (line 8) 'not motor' happened 0.005 s after entry 1's match, before the "
                                 "earliest 0.006 s: motor (Y0) is OFF"))
      << early.failure;
  // No headline of any of these ends on an empty reason.
  for (const CaseResult* r : {&never, &stale, &stale2, &early_rise, &late, &early})
    EXPECT_NE(r->failure.back(), ' ') << r->failure;
}

// A failure names a signal and its address together, "motor (Y0)", whichever the scenario
// wrote, in the headline and in the last changes; an address no signal names stays as written.
TEST(ScenarioRunner, ReportsShowSignalNamesBesideAddresses) {
  ScenarioCell cell("labels");
  const CaseResult r = cell.run(
      "      - set: {X0: on}\n"
      "      - after: 2ms\n"
      "      - expect: not Y0 and R101 == 1 and not X0\n");
  ASSERT_FALSE(r.passed);
  EXPECT_TRUE(has(r.failure, "s.yaml:7: expect not Y0 and R101 == 1 and not X0: not Y0 (motor (Y0) is ON); "
                             "R101 == 1 (R101 is 0); not X0 (start (X0) is ON)"))
      << r.failure;
  EXPECT_TRUE(has(r.details, "    motor (Y0):  initially OFF  0.000 s ON\n")) << r.details;
  EXPECT_TRUE(has(r.details, "    R101:  initially 0\n")) << r.details;
  EXPECT_TRUE(has(r.details, "    start (X0):  initially OFF  0.000 s ON\n")) << r.details;
}

TEST(ScenarioRunner, PulseHoldsItsWidthThenReleases) {
  ScenarioCell cell("pulse");
  // A 3 ms pulse from the scan at 0: on at 0, 1, 2 ms, off from 3 ms.
  const CaseResult r = cell.run(
      "      - pulse: {start: 3ms}\n"
      "      - expect: motor\n        within: 0s\n"
      "      - expect: motor\n        stays: 2ms\n"
      "      - after: 1ms\n        expect: not motor\n");
  EXPECT_TRUE(r.passed) << r.failure << r.details;
}

TEST(ScenarioRunner, RampWritesALinearValueBeforeEveryScan) {
  ScenarioCell cell("ramp");
  // From the scan at 0 to the scan at 1 s: 0 -> 1000, so 1 per ms.
  const CaseResult r = cell.run(
      "      - ramp: {R100: {from: 0, to: 1000, over: 1s}}\n"
      "      - expect: R100 == 0\n"
      "      - at: 250ms\n        expect: R100 == 250 and R101 == 250\n"
      "      - at: 2s\n        expect: R100 == 1000\n");
  EXPECT_TRUE(r.passed) << r.failure << r.details;
  // A later set of the same point ends the ramp.
  const CaseResult s = cell.run(
      "      - ramp: {R100: {from: -100, to: 100, over: 1s}}\n"
      "      - at: 100ms\n        set: {R100: 5}\n"
      "      - at: 500ms\n        expect: R100 == 5\n");
  EXPECT_TRUE(s.passed) << s.failure << s.details;
}

TEST(ScenarioRunner, ForceHoldsAPointUntilReleased) {
  ScenarioCell cell("force");
  const CaseResult r = cell.run(
      "      - force: {motor: on}\n"
      "      - expect: motor\n        stays: 10ms\n"
      "      - release: [motor]\n"
      "      - after: 1ms\n        expect: not motor\n"
      "      - force: {M5: on, Y7: off}\n"
      "      - release: all\n"
      "      - after: 1ms\n        expect: not M5\n");
  EXPECT_TRUE(r.passed) << r.failure << r.details;
}

TEST(ScenarioRunner, NumberFormatsOfRegisters) {
  ScenarioCell cell("formats");
  const CaseResult r = cell.run(
      "      - write: {R100: -2, DR200: -100000, DR300:f32: 2.5, R7: 65535}\n"
      "      - expect: R100 == -2 and R100:u == 65534 and DR200 == -100000 and DR200:u == 4294867296\n"
      "      - expect: DR300:f32 == 2.5 and R7 == -1\n");
  EXPECT_TRUE(r.passed) << r.failure << r.details;
  const CaseResult range = cell.run("      - write: {R100: 70000}\n");
  ASSERT_FALSE(range.passed);
  EXPECT_TRUE(has(range.failure, "write: R100: value 70000 out of range -32768..65535")) << range.failure;
}

TEST(ScenarioRunner, ATimeInThePastFails) {
  ScenarioCell cell("past");
  const CaseResult r = cell.run("      - at: 1s\n      - at: 500ms\n");
  ASSERT_FALSE(r.passed);
  EXPECT_TRUE(has(r.failure, "s.yaml:6: at 0.500 s is before now (1.000 s)")) << r.failure;
}

TEST(ScenarioRunner, AFaultEndsTheCase) {
  // An endless backward jump trips the scan's loop budget: a runtime fault, the PLC stops.
  ScenarioCell cell("fault", "LBL L1\nORG X0\nJMP L1\nEND\n");
  const CaseResult r = cell.run("      - set: {start: on}\n      - at: 10ms\n");
  ASSERT_FALSE(r.passed);
  EXPECT_TRUE(has(r.failure, "the PLC stopped on a fault")) << r.failure;
  EXPECT_EQ(r.virtual_us, 0u);  // set before the first scan: the scan at 0 loops
}

TEST(ScenarioRunner, FailureListsTheLastFiveChanges) {
  ScenarioCell cell("history");
  std::string steps;
  for (int i = 1; i <= 8; ++i) steps += "      - at: " + std::to_string(i) + "0ms\n        write: {R100: " + std::to_string(i) + "}\n";
  steps += "      - after: 1ms\n        expect: R101 == 0\n";
  const CaseResult r = cell.run(steps);
  ASSERT_FALSE(r.passed);
  EXPECT_TRUE(has(r.details, "R101:  0.041 s 4  0.051 s 5  0.061 s 6  0.071 s 7  0.081 s 8\n")) << r.details;
}

TEST(ScenarioRunner, TheSameCaseGivesTheSameResult) {
  ScenarioCell cell("determinism");
  const std::string steps =
      "      - pulse: {hold: 700ms}\n"
      "      - ramp: {R100: {from: 0, to: 30000, over: 2s}}\n"
      "      - wait_until: R101 > 20000 and done\n        timeout: 300ms\n";
  const CaseResult a = cell.run(steps), b = cell.run(steps);
  ASSERT_FALSE(a.passed);
  EXPECT_EQ(a.failure, b.failure);
  EXPECT_EQ(a.details, b.details);
  EXPECT_EQ(a.virtual_us, b.virtual_us);
}

TEST(ScenarioRunner, AnalogInputsAreDriven) {
  ScenarioCell cell("analog", "ORG M1925\nMOV S=R3840 D=R0\nEND\n",
                    "modules:\n"
                    "  analog:\n"
                    "    modules:\n"
                    "      - type: 6AD\n"
                    "        code: unipolar\n"
                    "        signal: unipolar\n"
                    "        span: 10\n"
                    "        inputs: [{name: level, value: 0 V}, {name: flow, value: 4 mA}]\n");
  // docs/analog-and-temperature.md: 5 V reads 8192 on a unipolar 0-10 V input.
  const CaseResult r = cell.run(
      "      - set: {analog.level: 5 V}\n"
      "      - after: 20ms\n        expect: R3840 == 8192\n");
  EXPECT_TRUE(r.passed) << r.failure << r.details;
  const CaseResult unit = cell.run("      - set: {analog.flow: 5 V}\n");
  ASSERT_FALSE(unit.passed);
  EXPECT_TRUE(has(unit.failure, "analog.flow: analog input 'flow' is a current (mA) input")) << unit.failure;
}

TEST(ScenarioRunner, TemperatureChannelsTakeDegreesOrTheSensorsSignal) {
  // The oven's 2TC reads both channels every 2 s; a K thermocouple gives 4.096 mV at
  // 100.0 degC (NIST ITS-90 table, against a 0 degC reference).
  const std::string src = PLC_CELL_SOURCE_DIR;
  const Scenario sc = parse_scenario(
      "cell: " + src + "/examples/oven/oven.yaml\n"
      "cases:\n"
      "  - name: c\n"
      "    steps:\n"
      "      - set: {temperature.box_temp: 4.096 mV, temperature.oven_temp: 150 C}\n"
      "      - at: 2.5s\n"
      "        expect: temperature.box_temp == 100 C +- 0.1 and temperature.oven_temp == 150 C +- 0.1 and R0 == 1500\n"
      "      - set: {temperature.box_temp: 80 ohm}\n",
      "/tmp/oven_t.yaml");
  CellTarget t(sc.cell, sc.program);
  const CaseResult r = run_case(sc.cases.at(0), t);
  ASSERT_FALSE(r.passed);
  EXPECT_TRUE(has(r.failure, "/tmp/oven_t.yaml:8: set: temperature.box_temp: channel 'box_temp' has a thermocouple: give C or mV"))
      << r.failure << r.details;
  EXPECT_EQ(r.virtual_us, 2500000u);  // the expectation before it held
}
