// The pulse probe (pulse.Xn.width, .period, .frequency): a scenario reads a counter
// input's pulse measurement as ~pulses/Xn shows it (docs/testing-your-cell.md).
#include <gtest/gtest.h>

#include "plc_cell/core/error.h"
#include "plc_cell/scenario/probe.h"
#include "scenario_fixture.h"

using namespace plc_cell;
using namespace plc_cell::scenario;
using plc_cell::testing::ScenarioCell;

namespace {

// HSC1 counts X4, driven by a 1 kHz generator (50 % duty); X4 is measured in us.
const char* kPulses =
    "counters:\n"
    "  hsc1: {mode: MD0, name: spindle}\n"
    "  sources:\n"
    "    - {name: gen, a: X4, hz: 1000}\n"
    "  pulse_measurement: {inputs: [X4]}\n";

TEST(PulseProbe, ParsesInputAndValue) {
  Probe p = parse_probe("pulse.X4.period");
  EXPECT_EQ(p.kind, Probe::Kind::PulsePeriod);
  EXPECT_EQ(p.name, "X4");
  EXPECT_EQ(parse_probe("pulse.x4.width").kind, Probe::Kind::PulseWidth);
  EXPECT_EQ(parse_probe("pulse.X4.width").name, "X4");
  EXPECT_EQ(parse_probe("pulse.X4.frequency").kind, Probe::Kind::PulseFrequency);
  try {
    parse_probe("pulse.X4.duty");
    ADD_FAILURE() << "pulse.X4.duty parsed";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "'pulse.X4.duty': a pulse measurement is read as pulse.Xn.width, .period or .frequency");
  }
  try {
    parse_probe("pulse.Y0.width");
    ADD_FAILURE() << "pulse.Y0.width parsed";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "'pulse.Y0.width': 'Y0' is not an input such as X0");
  }
}

TEST(PulseProbe, ReadsTheMeasurementWhileTheCounterCounts) {
  ScenarioCell cell("pulse_probe", plc_cell::testing::kTestProgram, kPulses);
  // Nothing before the second rising edge (1 ms, 2 ms); then period 1000 us, width 500 us.
  const CaseResult r = cell.run(
      "      - expect: pulse.X4.period == 0 and pulse.X4.frequency == 0\n"
      "      - after: 1ms\n"
      "        expect: pulse.X4.width == 0\n"
      "      - after: 1ms\n"
      "        expect: pulse.X4.period == 1000 and pulse.X4.width == 500 and pulse.X4.frequency == 1000\n"
      "      - after: 8ms\n"
      "        expect: counter.spindle == 10 and pulse.X4.period == 1000\n");
  EXPECT_TRUE(r.passed) << r.failure << r.details;
}

TEST(PulseProbe, AnInputThatIsNotMeasuredIsRefusedBeforeTheCaseRuns) {
  ScenarioCell cell("pulse_probe_unmeasured", plc_cell::testing::kTestProgram, kPulses);
  const Scenario sc = cell.parse("      - expect: pulse.X5.period == 0\n");
  CellTarget t(sc.cell, sc.program);
  const auto errors = check_case(sc.cases.at(0), t);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].to_string().find("X5 is not measured (counters.pulse_measurement.inputs)"), std::string::npos)
      << errors[0].to_string();
}

}  // namespace
