// An input that a scenario sets is the scenario's for the rest of the case, also on X0-X15,
// whose simulated steps and pulses reach the counters and interrupts as exact edges; the
// `simulate` step hands it back (docs/testing-your-cell.md "Inputs", docs/cell-config.md
// "Simulation"). Expected times and counts are worked out by hand from the signals below.
#include <gtest/gtest.h>

#include "scenario_fixture.h"

using namespace plc_cell;
using namespace plc_cell::scenario;
using plc_cell::testing::ScenarioCell;

namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// R0 counts the falling edges of X1 (its edge interrupt); hsc4 counts the rising edges of X4.
constexpr const char* kProgram =
    "ORG M1925\nOUT M0\nEND\n"
    "LBL X1-I\nORG M1925\nFUN 15 INC D=R0\nRTI\n";

}  // namespace

TEST(SimulatedInputs, SetTakesAnX0ToX15StepsInputWithItsEdgeInterrupt) {
  // The simulation: X1 ON at 0, OFF at 4 s, ON at 6 s, OFF at 8 s.
  ScenarioCell cell("sim_steps", kProgram,
                    "simulation:\n  inputs:\n    hold: {steps: [[0.0, 1], [4.0, 0], [6.0, 1], [8.0, 0]]}\n"
                    "counters:\n  interrupts: [X1-]\n");
  const CaseResult r = cell.run(
      "      - at: 1s\n"
      "        set: {hold: on}\n"
      "      - at: 4.05s\n"  // the simulation's 4 s edge reaches neither the image nor X1-I
      "        expect: hold and R0 == 0\n"
      "      - set: {hold: off}\n"  // the scenario's own edge is a real one: X1-I runs
      "      - after: 1ms\n"
      "        expect: not hold and R0 == 1\n"
      "      - at: 6.05s\n"
      "        expect: not hold\n"
      "      - simulate: [hold]\n"  // the simulation's level now (ON since 6 s), at the next scan
      "      - after: 1ms\n"
      "        expect: hold and R0 == 1\n"
      "      - at: 8.05s\n"  // and its later edges land again
      "        expect: not hold and R0 == 2\n");
  EXPECT_TRUE(r.passed) << r.failure << r.details;
}

TEST(SimulatedInputs, TheIssuesReportReadsOnAtFourPointZeroFive) {
  ScenarioCell cell("sim_report", kProgram, "simulation:\n  inputs:\n    X1: {steps: [[0.0, 1], [4.0, 0]]}\n");
  const CaseResult r = cell.run(
      "      - set: {X1: on}\n"
      "      - at: 4.05s\n"
      "        expect: X1\n");
  EXPECT_TRUE(r.passed) << r.failure << r.details;
}

TEST(SimulatedInputs, SetTakesAnX0ToX15PulseInputFromItsCounter) {
  // Rising edges at 0.01 + 0.1 k s, 50 ms ON.
  ScenarioCell cell("sim_pulse", kProgram,
                    "simulation:\n  inputs:\n    X4: {pulse: {period: 0.1, width: 0.05, delay: 0.01}}\n"
                    "counters:\n  hsc4: {mode: MD0, a: X4, name: parts}\n");
  const CaseResult r = cell.run(
      "      - at: 1.02s\n"  // 0.01 ... 1.01 s: 11 rising edges; ON since 1.01 s
      "        expect: counter.parts == 11 and X4\n"
      "      - set: {X4: off}\n"
      "      - at: 2s\n"
      "        expect: counter.parts == 11 and not X4\n"
      "        stays: 500ms\n"
      "      - simulate: X4\n"  // at 2.5 s the train is OFF (ON 2.41-2.46 s, next 2.51 s)
      "      - after: 5ms\n"
      "        expect: not X4 and counter.parts == 11\n"
      "      - at: 3.02s\n"  // 2.51 ... 3.01 s: 6 more
      "        expect: counter.parts == 17 and X4\n");
  EXPECT_TRUE(r.passed) << r.failure << r.details;
}

TEST(SimulatedInputs, HandBackTakesThePulsesLevelAtOnce) {
  ScenarioCell cell("sim_pulse_level", kProgram,
                    "simulation:\n  inputs:\n    X4: {pulse: {period: 0.1, width: 0.05, delay: 0.01}}\n"
                    "counters:\n  hsc4: {mode: MD0, a: X4, name: parts}\n");
  const CaseResult r = cell.run(
      "      - set: {X4: off}\n"
      "      - at: 1.02s\n"
      "        expect: counter.parts == 0 and not X4\n"
      "      - simulate: all\n"  // the train is ON from 1.01 to 1.06 s: a rising edge at the next scan
      "      - after: 1ms\n"
      "        expect: X4 and counter.parts == 1\n");
  EXPECT_TRUE(r.passed) << r.failure << r.details;
}

TEST(SimulatedInputs, SimulateHandsBackScanSampledInputsAndEndsAPulse) {
  // X20 is beyond the high-speed inputs: the simulation sets it before every scan.
  ScenarioCell cell("sim_x20", kProgram, "simulation:\n  inputs:\n    X20: {steps: [[0.0, 1]]}\n");
  const CaseResult r = cell.run(
      "      - set: {X20: off}\n"
      "      - after: 1ms\n"
      "        expect: not X20\n"
      "        stays: 200ms\n"
      "      - pulse: {X20: 1s}\n"  // ON from 0.202 s, OFF at 1.202 s unless it ends before
      "      - at: 500ms\n"
      "        simulate: [X20]\n"  // the simulation's ON, and the pulse ends here
      "      - at: 1.5s\n"
      "        expect: X20\n");
  EXPECT_TRUE(r.passed) << r.failure << r.details;
}

TEST(SimulatedInputs, SimulateRefusesWhatTheSimulationDoesNotPlay) {
  ScenarioCell cell("sim_refused", kProgram, "simulation:\n  inputs:\n    X20: {steps: [[0.0, 1]]}\n");
  const CaseResult none = cell.run("      - simulate: [start]\n");
  ASSERT_FALSE(none.passed);
  EXPECT_TRUE(has(none.failure, "s.yaml:5: simulate: start: the cell's simulation: has no signal on X0")) << none.failure;
  const CaseResult output = cell.run("      - simulate: [motor]\n");
  ASSERT_FALSE(output.passed);
  EXPECT_TRUE(has(output.failure, "motor: only an input (X) is simulated")) << output.failure;
  EXPECT_THROW(cell.parse("      - simulate: {X20: on}\n"), SourceError);
}
