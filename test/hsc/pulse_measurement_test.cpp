// Pulse measurement (TRi FMD1616 Ch. 8: PULSEWIDTH, PULSEPERIOD, PULSEFREQUENCY) on
// counter inputs: exact edge lists, analytic sources, both units, the first pulse and
// the 0 Hz rule (docs/counters-and-interrupts.md "Pulse measurement"), in virtual time.
#include "hsc_fixture.h"

#include "plc_cell/core/error.h"
#include "plc_cell/hsc/pulse_meter.h"

namespace plc_cell {
namespace hsc {
namespace {

constexpr uint64_t kUs = 1000;     // ns
constexpr uint64_t kMs = 1000000;  // ns

const char* kIdle = "ORG M1925\nOUT M0\nEND\n";

// ---- the meter alone -------------------------------------------------------------

TEST(PulseMeter, WidthAndPeriodOfTheLastFullCycleFromAnEdgeList) {
  PulseMeter m;
  // 300 us ON every 1 ms (30 % duty), then 100 us ON every 400 us (25 %).
  const uint64_t rises[] = {1 * kMs, 2 * kMs, 3 * kMs};
  for (uint64_t r : rises) {
    m.edge(r, true);
    m.edge(r + 300 * kUs, false);
  }
  PulseReading r = m.read(3 * kMs + 500 * kUs);
  EXPECT_EQ(r.width_ns, 300 * kUs);
  EXPECT_EQ(r.period_ns, 1 * kMs);
  EXPECT_EQ(r.frequency_hz, 1000.0);
  m.edge(3400 * kUs, true);  // the cycle 3.0 .. 3.4 ms: ON 300 us of 400 us
  m.edge(3500 * kUs, false);
  r = m.read(3500 * kUs);
  EXPECT_EQ(r.width_ns, 300 * kUs);
  EXPECT_EQ(r.period_ns, 400 * kUs);
  EXPECT_EQ(r.frequency_hz, 2500.0);
  m.edge(3800 * kUs, true);  // 3.4 .. 3.8 ms: ON 100 us of 400 us
  r = m.read(3800 * kUs);
  EXPECT_EQ(r.width_ns, 100 * kUs);
  EXPECT_EQ(r.period_ns, 400 * kUs);
  EXPECT_EQ(r.frequency_hz, 2500.0);
}

TEST(PulseMeter, NothingBeforeTheSecondRisingEdge) {
  PulseMeter m;
  EXPECT_EQ(m.read(0).period_ns, 0u);
  m.edge(1 * kMs, false);  // ON since before the start: not a pulse of its own
  m.edge(2 * kMs, true);
  m.edge(2 * kMs + 200 * kUs, false);  // a whole first pulse, but no period yet
  PulseReading r = m.read(5 * kMs);
  EXPECT_EQ(r.width_ns, 0u);
  EXPECT_EQ(r.period_ns, 0u);
  EXPECT_EQ(r.frequency_hz, 0.0);
  m.edge(7 * kMs, true);  // the first cycle, however long (no period to scale a timeout)
  r = m.read(7 * kMs);
  EXPECT_EQ(r.width_ns, 200 * kUs);
  EXPECT_EQ(r.period_ns, 5 * kMs);
  EXPECT_EQ(r.frequency_hz, 200.0);
}

TEST(PulseMeter, ZeroOnceNoRisingEdgeForTwiceTheLastPeriodThenStartsOver) {
  PulseMeter m;  // automatic timeout
  for (uint64_t t = 0; t <= 10 * kMs; t += 1 * kMs) {
    m.edge(t, true);
    m.edge(t + 500 * kUs, false);
  }
  EXPECT_EQ(m.read(12 * kMs).period_ns, 1 * kMs);  // 2 ms after the last rise: still held
  PulseReading r = m.read(12 * kMs + 1);           // later: 0 Hz
  EXPECT_EQ(r.width_ns, 0u);
  EXPECT_EQ(r.period_ns, 0u);
  EXPECT_EQ(r.frequency_hz, 0.0);
  m.edge(20 * kMs, true);  // back: a first edge again, no 10 ms "period"
  m.edge(20 * kMs + 100 * kUs, false);
  EXPECT_EQ(m.read(20 * kMs + 200 * kUs).period_ns, 0u);
  m.edge(20 * kMs + 400 * kUs, true);
  r = m.read(20 * kMs + 400 * kUs);
  EXPECT_EQ(r.width_ns, 100 * kUs);
  EXPECT_EQ(r.period_ns, 400 * kUs);
  EXPECT_EQ(r.frequency_hz, 2500.0);
}

TEST(PulseMeter, AConfiguredTimeoutReplacesTwiceThePeriod) {
  PulseMeter m(5 * kMs);
  m.edge(0, true);
  m.edge(500 * kUs, false);
  m.edge(1 * kMs, true);
  m.edge(1500 * kUs, false);
  EXPECT_EQ(m.read(6 * kMs).period_ns, 1 * kMs);  // 5 ms after the last rise
  EXPECT_EQ(m.read(6 * kMs + 1).period_ns, 0u);
  m.edge(4 * kMs, true);  // 3 ms after the last rise: within 5 ms, a period of its own
  PulseReading r = m.read(4 * kMs);
  EXPECT_EQ(r.width_ns, 500 * kUs);
  EXPECT_EQ(r.period_ns, 3 * kMs);
  // Also before a first period: a second rise later than the timeout is a first edge.
  PulseMeter f(5 * kMs);
  f.edge(0, true);
  f.edge(1 * kMs, false);
  f.edge(6 * kMs, true);
  EXPECT_EQ(f.read(6 * kMs).period_ns, 0u);
}

// ---- configuration -------------------------------------------------------------------

HscConfig parse(const std::string& text) { return parse_hsc_config(YAML::Load(text)["counters"], "cell.yaml"); }

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const SourceError& e) {
    return e.diagnostics().at(0).to_string();
  }
  return "";
}

TEST(PulseMeasurementConfig, InputsUnitAndTimeout) {
  HscConfig c = parse(
      "counters:\n"
      "  hsc0: {mode: MD7}\n"
      "  hsc4: {mode: MD0, a: X6, b: X7}\n"
      "  pulse_measurement: {inputs: [X0, x7], unit: 0.1us, timeout: 500ms}\n");
  EXPECT_EQ(c.pulse.inputs, (std::vector<int>{0, 7}));
  EXPECT_EQ(c.pulse.counter_of, (std::vector<int>{0, 4}));
  EXPECT_TRUE(c.pulse.tenths);
  EXPECT_STREQ(c.pulse.unit(), "0.1us");
  EXPECT_EQ(c.pulse.timeout_ns, 500 * kMs);
  EXPECT_TRUE(c.pulse.measured(7));
  EXPECT_FALSE(c.pulse.measured(1));
  // Defaults: us, automatic timeout; not configured: nothing measured.
  c = parse("counters:\n  hsc0: {mode: MD0}\n  pulse_measurement:\n    inputs: [X0]\n    timeout: auto\n");
  EXPECT_FALSE(c.pulse.tenths);
  EXPECT_STREQ(c.pulse.unit(), "us");
  EXPECT_EQ(c.pulse.timeout_ns, 0u);
  EXPECT_EQ(c.pulse.in_unit(1234 * 100), 123.4);
  c = parse("counters:\n  hsc0: {mode: MD0}\n");
  EXPECT_TRUE(c.pulse.inputs.empty());
}

TEST(PulseMeasurementConfig, ErrorsNameTheLineAndTheReason) {
  const std::string head = "counters:\n  hsc0: {mode: MD0}\n  hsc1: {type: timer}\n";
  EXPECT_EQ(error_of(head + "  pulse_measurement: {inputs: [X0, X9]}\n"),
            "cell.yaml:4:36: error: key 'counters.pulse_measurement.inputs': X9 is not a counting input of a "
            "configured counter; pulse measurement works on a counter's counting input (hscN.a or hscN.b)");
  // HSC0 in MD0 without b counts X0 only; X4 is HSC1's pin, but HSC1 is a timer.
  EXPECT_NE(error_of(head + "  pulse_measurement: {inputs: [X1]}\n").find("X1 is not a counting input"),
            std::string::npos);
  EXPECT_NE(error_of(head + "  pulse_measurement: {inputs: [X4]}\n").find("X4 is not a counting input"),
            std::string::npos);
  EXPECT_EQ(error_of(head + "  pulse_measurement: {inputs: [X0], unit: ms}\n"),
            "cell.yaml:4:43: error: key 'counters.pulse_measurement.unit': 'ms': expected us or 0.1us");
  std::string e = error_of(head + "  pulse_measurement: {inputs: [X0, X0]}\n");
  EXPECT_NE(e.find("cell.yaml:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("X0 is listed twice"), std::string::npos) << e;
  e = error_of(head + "  pulse_measurement: {inputs: [X16]}\n");
  EXPECT_NE(e.find("'X16': only X0-X15 are high-speed inputs"), std::string::npos) << e;
  e = error_of(head + "  pulse_measurement: {inputs: [Y0]}\n");
  EXPECT_NE(e.find("'Y0' is not an input X0-X15"), std::string::npos) << e;
  e = error_of(head + "  pulse_measurement: {inputs: []}\n");
  EXPECT_NE(e.find("expected a list of counting inputs"), std::string::npos) << e;
  e = error_of(head + "  pulse_measurement: {unit: us}\n");
  EXPECT_NE(e.find("cell.yaml:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("needs inputs:"), std::string::npos) << e;
  e = error_of(head + "  pulse_measurement: [X0]\n");
  EXPECT_NE(e.find("expected a mapping"), std::string::npos) << e;
  e = error_of(head + "  pulse_measurement: {inputs: [X0], timeout: 0ms}\n");
  EXPECT_NE(e.find("counters.pulse_measurement.timeout"), std::string::npos) << e;
  EXPECT_NE(e.find("at least 1us"), std::string::npos) << e;
  e = error_of(head + "  pulse_measurement: {inputs: [X0], timeout: soon}\n");
  EXPECT_NE(e.find("counters.pulse_measurement.timeout"), std::string::npos) << e;
  e = error_of(head + "  pulse_measurement: {inputs: [X0], units: us}\n");
  EXPECT_NE(e.find("cell.yaml:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("units"), std::string::npos) << e;
}

// ---- on the cell ------------------------------------------------------------------

PulseReading pulse_of(HscCell& cell, int x) {
  return cell.with([&](HscUnit& u) { return u.pulse(x); });
}

// Explicit edges on HSC4's U input X4: 2.5 kHz, 100 us ON. It counts every rising edge
// and measures the same pin at once (TRi §8.2.1, §8.3).
TEST(PulseMeasurement, ExactEdgesWhileCounting) {
  HscCell cell("counters:\n  hsc4: {mode: MD0, a: X4}\n  pulse_measurement: {inputs: [X4]}\n", kIdle);
  cell.with([&](HscUnit& u) {
    for (int k = 0; k < 20; ++k) {
      u.schedule_edge(4, 1 * kMs + k * 400 * kUs, true);
      u.schedule_edge(4, 1 * kMs + k * 400 * kUs + 100 * kUs, false);
    }
    return 0;
  });
  cell.run(1000, 1000);  // the scan at 0 ms: nothing yet
  EXPECT_EQ(pulse_of(cell, 4).period_ns, 0u);
  cell.run(1000, 1000);  // 1 ms: the first rising edge only
  EXPECT_EQ(pulse_of(cell, 4).period_ns, 0u);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(4); }), 1);
  cell.run(4000, 1000);  // to 5 ms
  PulseReading r = pulse_of(cell, 4);
  EXPECT_EQ(r.width_ns, 100 * kUs);
  EXPECT_EQ(r.period_ns, 400 * kUs);
  EXPECT_EQ(r.frequency_hz, 2500.0);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(4); }), 11);  // rises at 1.0 .. 5.0 ms
  EXPECT_EQ(cell.unit->config().pulse.in_unit(r.width_ns), 100.0);
  // The last rise is at 8.6 ms; 0 once more than 2 x 400 us have passed.
  cell.run(4000, 1000);  // scans 6 .. 9 ms
  EXPECT_EQ(pulse_of(cell, 4).period_ns, 400 * kUs);
  cell.run(1000, 1000);  // 10 ms
  r = pulse_of(cell, 4);
  EXPECT_EQ(r.width_ns, 0u);
  EXPECT_EQ(r.period_ns, 0u);
  EXPECT_EQ(r.frequency_hz, 0.0);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(4); }), 20);
  // An input that is not measured reads 0.
  EXPECT_EQ(pulse_of(cell, 5).frequency_hz, 0.0);
}

// The simulation's pulse train (`simulation.inputs` kind pulse): 25 % and 75 % duty.
TEST(PulseMeasurement, DutyCyclesOfPulseTrainsInTenthsOfAMicrosecond) {
  HscCell cell("counters:\n  hsc0: {mode: MD0}\n  hsc1: {mode: MD0}\n"
               "  pulse_measurement: {inputs: [X0, X4], unit: 0.1us}\n", kIdle);
  cell.with([&](HscUnit& u) {
    u.add_pulse_train(0, 1234 * 100, 3085 * 10, 0);   // 123.4 us period, 30.85 us ON (25 %)
    u.add_pulse_train(4, 4 * kMs, 3 * kMs, 1 * kMs);  // 250 Hz, 75 %
    return 0;
  });
  cell.run(20000, 1000);
  const HscConfig& cfg = cell.unit->config();
  PulseReading r = pulse_of(cell, 0);
  EXPECT_EQ(cfg.pulse.in_unit(r.period_ns), 1234.0);  // TRi: 1234 means 123.4 us
  EXPECT_EQ(cfg.pulse.in_unit(r.width_ns), 308.5);
  EXPECT_DOUBLE_EQ(r.frequency_hz, 1e9 / 123400.0);
  r = pulse_of(cell, 4);
  EXPECT_EQ(cfg.pulse.in_unit(r.period_ns), 40000.0);
  EXPECT_EQ(cfg.pulse.in_unit(r.width_ns), 30000.0);
  EXPECT_EQ(r.frequency_hz, 250.0);
}

// An analytic 1 kHz generator (50 % duty) on HSC0's U input: period 1/hz exactly, width
// half of it, while HSC0 counts; the first full cycle ends at the second rising edge.
TEST(PulseMeasurement, AnalyticSourceWhileCounting) {
  HscCell cell("counters:\n  hsc0: {mode: MD0}\n  sources:\n    - {name: gen, a: X0, hz: 1000}\n"
               "  pulse_measurement: {inputs: [X0]}\n", kIdle);
  cell.run(2000, 1000);  // ON from the start (no edge), rises at 1 ms: no full cycle at 1 ms
  EXPECT_EQ(pulse_of(cell, 0).period_ns, 0u);
  cell.run(1000, 1000);  // 2 ms: the second rise
  PulseReading r = pulse_of(cell, 0);
  EXPECT_EQ(r.period_ns, 1 * kMs);
  EXPECT_EQ(r.width_ns, 500 * kUs);
  EXPECT_EQ(r.frequency_hz, 1000.0);
  cell.run(97000, 1000);  // to 99 ms
  r = pulse_of(cell, 0);
  EXPECT_EQ(r.period_ns, 1 * kMs);
  EXPECT_EQ(r.width_ns, 500 * kUs);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 99);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.config().pulse.in_unit(u.pulse(0).period_ns); }), 1000.0);
}

// Both phases of a fast A/B x4 encoder, with 10 ms scans: exact, whatever the number of
// cycles between two scans.
TEST(PulseMeasurement, BothPhasesOfAFastEncoder) {
  HscCell cell("counters:\n  hsc0: {mode: MD7}\n  sources:\n    - {name: enc, type: encoder, a: X0, hz: 40000}\n"
               "  pulse_measurement: {inputs: [X0, X1], unit: 0.1us}\n", kIdle);
  cell.run(100000, 10000);
  for (int x : {0, 1}) {
    const PulseReading r = pulse_of(cell, x);
    EXPECT_EQ(r.period_ns, 25 * kUs) << x;
    EXPECT_EQ(r.width_ns, 12500u) << x;
    EXPECT_EQ(r.frequency_hz, 40000.0) << x;
  }
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 4 * 40000 * 90 / 1000);  // to the 90 ms scan
}

// A rate change: 1 kHz -> 400 Hz at 9 ms. Automatic timeout (2 x 1 ms): the 2.5 ms gap
// reads 0 from 11 ms, and the 400 Hz period appears at the next full cycle (14 ms).
TEST(PulseMeasurement, SlowingBelowHalfTheFrequencyReadsZeroForOneCycle) {
  HscCell cell("counters:\n  hsc0: {mode: MD0}\n  sources:\n    - {name: gen, a: X0, hz: 1000}\n"
               "  pulse_measurement: {inputs: [X0]}\n", kIdle);
  cell.run(10000, 1000);  // scans 0 .. 9 ms; a rise at 9 ms
  cell.with([](HscUnit& u) {
    u.set_source_rate("gen", 400);
    return 0;
  });
  cell.run(3000, 1000);  // 10, 11, 12 ms
  EXPECT_EQ(pulse_of(cell, 0).period_ns, 0u);   // 12 ms: 3 ms since the rise at 9 ms
  cell.run(2000, 1000);  // 13, 14 ms: rises at 11.5 ms (first again) and 14 ms
  const PulseReading r = pulse_of(cell, 0);
  EXPECT_EQ(r.period_ns, 2500 * kUs);
  EXPECT_EQ(r.width_ns, 1250 * kUs);
  EXPECT_EQ(r.frequency_hz, 400.0);
}

TEST(PulseMeasurement, ReadsTheLastPeriodUntilTheTimeoutAtExactlyTwicePeriod) {
  HscCell cell("counters:\n  hsc0: {mode: MD0}\n  sources:\n    - {name: gen, a: X0, hz: 1000}\n"
               "  pulse_measurement: {inputs: [X0]}\n", kIdle);
  cell.run(10000, 1000);  // scans 0 .. 9 ms
  cell.with([](HscUnit& u) {
    u.set_source_rate("gen", 400);
    return 0;
  });
  cell.run(2000, 1000);  // 10, 11 ms: 11 ms is exactly 2 x 1 ms after the rise at 9 ms
  EXPECT_EQ(pulse_of(cell, 0).period_ns, 1 * kMs);
}

// A configured timeout: the slower period is measured at once (within 5 ms), and a
// source that stops reads 0 five ms after its last rising edge.
TEST(PulseMeasurement, ConfiguredTimeoutAndAStoppedSource) {
  HscCell cell("counters:\n  hsc0: {mode: MD0}\n  sources:\n    - {name: gen, a: X0, hz: 1000}\n"
               "  pulse_measurement: {inputs: [X0], timeout: 5ms}\n", kIdle);
  cell.run(10000, 1000);
  cell.with([](HscUnit& u) {
    u.set_source_rate("gen", 400);
    return 0;
  });
  cell.run(3000, 1000);  // 12 ms: the rise at 11.5 ms closed the cycle 9 .. 11.5 ms
  PulseReading r = pulse_of(cell, 0);
  EXPECT_EQ(r.period_ns, 2500 * kUs);
  EXPECT_EQ(r.width_ns, 1250 * kUs);
  cell.run(3000, 1000);  // 15 ms; the last rise at 14 ms
  cell.with([](HscUnit& u) {
    u.set_source_rate("gen", 0);  // stopped at 15 ms, ON (the fall would be at 15.25 ms)
    return 0;
  });
  cell.run(4000, 1000);  // 16 .. 19 ms: within 5 ms of 14 ms
  EXPECT_EQ(pulse_of(cell, 0).period_ns, 2500 * kUs);
  cell.run(1000, 1000);  // 20 ms: 6 ms
  r = pulse_of(cell, 0);
  EXPECT_EQ(r.period_ns, 0u);
  EXPECT_EQ(r.width_ns, 0u);
  EXPECT_EQ(r.frequency_hz, 0.0);
}

// A follow source (a motor's encoder): 0 Hz while the motor is off, measured once on.
TEST(PulseMeasurement, FollowSourceFromStandstill) {
  HscCell cell("counters:\n  hsc0: {mode: MD0}\n  sources:\n    - {name: gen, a: X0, hz: 2000, follow: Y0}\n"
               "  pulse_measurement: {inputs: [X0]}\n",
               "ORG M100\nOUT Y0\nEND\n");
  cell.run(10000, 1000);
  EXPECT_EQ(pulse_of(cell, 0).frequency_hz, 0.0);
  cell.put("M100", 1);
  cell.run(1000, 1000);  // Y0 on at the end of the 10 ms scan: ON at rest, falls 10.25 ms
  EXPECT_EQ(pulse_of(cell, 0).frequency_hz, 0.0);
  cell.run(1000, 1000);  // 11 ms: rises at 10.5 and 11 ms
  const PulseReading r = pulse_of(cell, 0);
  EXPECT_EQ(r.period_ns, 500 * kUs);
  EXPECT_EQ(r.width_ns, 250 * kUs);
  EXPECT_EQ(r.frequency_hz, 2000.0);
}

// A source faster than the input's filter is lost (the input stays OFF): nothing measured.
TEST(PulseMeasurement, ASourceAboveTheFilterCutOffIsNotMeasured) {
  HscCell cell("counters:\n  hsc0: {mode: MD0}\n  filters: {X0-X3: 28kHz}\n"
               "  sources:\n    - {name: gen, a: X0, hz: 40000}\n"
               "  pulse_measurement: {inputs: [X0]}\n", kIdle);
  cell.run(10000, 1000);
  EXPECT_EQ(pulse_of(cell, 0).frequency_hz, 0.0);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 0);
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
