// The rules of a scenario run in wall-clock time on a PLC over a link
// (docs/testing-on-hardware.md): the refusals at file:line, the windows against the
// resolution and --tolerance, what a case touches, the target's polls and drives, and the
// runner's time following a target whose poll came late.
#include <gtest/gtest.h>

#include "memory_plc.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/scenario/resolution.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/scenario_file.h"
#include "plc_cell/scenario/wall_clock.h"
#include "plc_cell/scenario/wall_clock_target.h"

using namespace plc_cell;
using namespace plc_cell::scenario;
using plc_cell::scenario_test::MemoryPlc;

namespace {

CellConfig config() {
  return parse_cell_config("cell: {name: t, program: t.il}\nsignals: {start: X0, part: X3, motor: Y0, latch: M0}\n",
                           "/d/t.yaml", Cell::sections());
}

Case first_case(const std::string& text) { return parse_scenario("cell: t.yaml\n" + text, "/d/s.yaml").cases.at(0); }

std::vector<std::string> texts(const std::vector<Diagnostic>& ds) {
  std::vector<std::string> out;
  for (const auto& d : ds) out.push_back(d.to_string());
  return out;
}

WallClockRules rules(std::optional<uint64_t> resolution_us, uint64_t tolerance_us = 0, std::string no_force = "") {
  return {"the PLC", std::move(no_force), resolution_us, tolerance_us};
}

}  // namespace

TEST(WallClockRules, StepsATargetCannotDoAreRefusedAtTheirLine) {
  const Case c = first_case(
      "cases:\n"
      "  - name: a\n"
      "    steps:\n"
      "      - simulate: [part]\n"                       // line 5
      "      - set: {temperature.oven: 4.1 mV}\n"        // line 6
      "      - set: {part: on, latch: on}\n"             // line 7: an input held, a relay written
      "      - force: {motor: off}\n"                    // line 8
      "      - release: all\n");                         // line 9
  const Preflight held = wall_clock_preflight(c, rules(std::nullopt), config());
  EXPECT_EQ(texts(held.errors),
            (std::vector<std::string>{
                "/d/s.yaml:5: error: key 'simulate': a real cell has no simulation to hand inputs back to: its PLC "
                "reads them from its terminals (a case drives an input with set, and frees it with release)",
                "/d/s.yaml:6: error: key 'set': temperature.oven: '4.1 mV' is a signal of the cell's simulated module: "
                "the PLC cannot drive a sensor over its link (write the registers behind it, or drive the sensor itself)"}));
  // A link with no force cannot hold the input, nor force, nor release; the relay is written.
  const Preflight no_force = wall_clock_preflight(c, rules(std::nullopt, 0, "this link has no force"), config());
  const auto e = texts(no_force.errors);
  ASSERT_EQ(e.size(), 5u);
  EXPECT_EQ(e[2], "/d/s.yaml:7: error: key 'set': part (X3): the PLC cannot hold it: this link has no force");
  EXPECT_EQ(e[3], "/d/s.yaml:8: error: key 'force': motor (Y0): the PLC cannot hold it: this link has no force");
  EXPECT_EQ(e[4], "/d/s.yaml:9: error: key 'release': the PLC has nothing to release: this link has no force");
}

TEST(WallClockRules, WindowsTighterThanTheResolutionAreRefusedOrWidenedWithinTheTolerance) {
  const Case c = first_case(
      "properties:\n"
      "  - never: motor and latch\n"                                // line 3: no grace
      "  - always: motor\n"                                         // line 4
      "    within: 1ms\n"
      "cases:\n"
      "  - name: a\n"
      "    steps:\n"
      "      - expect: motor\n"                                     // line 9
      "        within: 0s\n"
      "      - expect: motor\n"                                     // line 11
      "        between: [1.5s, 1.501s]\n"
      "      - expect: motor\n"                                     // line 13: wide enough
      "        within: 200ms\n"
      "      - pulse: {start: 2ms}\n"                               // line 15
      "      - expect_sequence:\n"                                  // line 16
      "          - {that: motor, within: 1ms}\n"                    // line 17
      "          - {that: latch, between: [1s, 2s]}\n"
      "        timeout: 5s\n");
  // Unknown resolution (a dry run): nothing is checked.
  EXPECT_TRUE(wall_clock_preflight(c, rules(std::nullopt), config()).errors.empty());
  const Preflight refused = wall_clock_preflight(c, rules(3000), config());
  EXPECT_EQ(texts(refused.errors),
            (std::vector<std::string>{
                "/d/s.yaml:9: error: key 'expect': within 0 ms is tighter than the resolution 3 ms of the PLC: widen "
                "it in the file, or let --tolerance 3ms widen it",
                "/d/s.yaml:11: error: key 'expect': between [1.500 s, 1.501 s] is tighter than the resolution 3 ms of "
                "the PLC: widen it in the file, or let --tolerance 2ms widen it",
                "/d/s.yaml:15: error: key 'pulse': a pulse of 2 ms on start is tighter than the resolution 3 ms of "
                "the PLC: widen it in the file, or let --tolerance 1ms widen it",
                "/d/s.yaml:17: error: key 'expect_sequence': entry 1's within 1 ms is tighter than the resolution "
                "3 ms of the PLC: widen it in the file, or let --tolerance 2ms widen it"}));
  // A tolerance too small for the widest need refuses only that one, and says so.
  EXPECT_EQ(wall_clock_preflight(c, rules(3000, 2000), config()).errors.size(), 1u);
  // Every property, whatever the tolerance, is checked with at least the resolution as its
  // grace: said, not refused.
  EXPECT_EQ(texts(refused.errors).size(), 4u);
  EXPECT_EQ(refused.widened.size(), 2u);
  const Preflight widened = wall_clock_preflight(c, rules(3000, 3000), config());
  EXPECT_TRUE(widened.errors.empty());
  ASSERT_EQ(widened.widened.size(), 6u);
  EXPECT_EQ(widened.widened[0].to_string(),
            "/d/s.yaml:3: property never: motor and latch: no grace, checked with the resolution 3 ms as its grace");
  EXPECT_EQ(widened.widened[1].to_string(),
            "/d/s.yaml:4: property always: motor: its grace within 1 ms, checked with the resolution 3 ms as its grace");
  EXPECT_EQ(widened.widened[2].to_string(),
            "/d/s.yaml:9: within 0 ms widened by 3 ms to the resolution 3 ms (--tolerance 3ms)");
  const Case& a = widened.adjusted;
  EXPECT_EQ(a.steps[0].window_max_us, 3000u);
  EXPECT_EQ(a.steps[1].window_min_us, 1500000u);
  EXPECT_EQ(a.steps[1].window_max_us, 1503000u);
  EXPECT_EQ(a.steps[2].window_max_us, 200000u);  // untouched
  EXPECT_EQ(a.steps[3].assignments[0].duration_us, 3000u);
  EXPECT_EQ(a.steps[4].sequence[0].max_us, 3000u);
  EXPECT_EQ(a.steps[4].sequence[1].max_us, 2000000u);
  EXPECT_EQ(a.properties[1].within_us, 3000u);
  EXPECT_EQ(a.properties[0].within_us, 3000u);
}

TEST(WallClockRules, WhatACaseTouchesAndWritesIsListedWithItsLines) {
  const Case c = first_case(
      "cases:\n"
      "  - name: a\n"
      "    steps:\n"
      "      - set: {part: on, R100: 5}\n"        // line 5
      "      - pulse: {start: 100ms}\n"           // line 6
      "      - force: {motor: off}\n"             // line 7
      "      - release: [motor]\n"                // line 8
      "      - write: {latch: on}\n"              // line 9
      "      - expect: motor\n");
  const auto points = touched_points(c, config());
  ASSERT_EQ(points.size(), 5u);
  EXPECT_EQ(points[0].label, "part (X3)");
  EXPECT_TRUE(points[0].held);
  EXPECT_EQ(points[1].label, "R100");
  EXPECT_FALSE(points[1].held);
  EXPECT_TRUE(points[2].held);   // start: pulsed input
  EXPECT_TRUE(points[3].held);   // motor: forced
  EXPECT_FALSE(points[4].held);  // latch: written
  std::vector<std::string> plan;
  for (const auto& n : planned_actions(c, config())) plan.push_back(n.to_string());
  EXPECT_EQ(plan, (std::vector<std::string>{
                      "/d/s.yaml:5: force part (X3) ON (held as its terminal)", "/d/s.yaml:5: write R100 = 5",
                      "/d/s.yaml:6: force start (X0) ON, then OFF after 100 ms", "/d/s.yaml:7: force motor (Y0) OFF",
                      "/d/s.yaml:8: release motor (Y0)", "/d/s.yaml:9: write latch (M0) = on"}));
}

TEST(HardwarePermission, TrueAListOrAMappingAndWhatEachAllows) {
  auto read = [](const std::string& h) { return parse_scenario("cell: t.yaml\n" + h + "cases: [{name: a, steps: [{at: 1s}]}]\n", "/d/s.yaml").hardware; };
  const HardwarePermission none = read("");
  EXPECT_EQ(none.line, 0);
  EXPECT_NE(none.refuses("fatek://a:500").find("add 'hardware: true'"), std::string::npos);
  EXPECT_EQ(read("hardware: true\n").refuses("fatek://a:500"), "");
  EXPECT_EQ(read("hardware: false\n").refuses("fatek://a:500"), "this file says 'hardware: false': it runs in virtual time only");
  const HardwarePermission list = read("hardware: [fatek://10.0.0.5:*, tri-serial:/dev/ttyUSB0]\n");
  EXPECT_EQ(list.refuses("fatek://10.0.0.5:500"), "");
  EXPECT_EQ(list.refuses("tri-serial:/dev/ttyUSB0"), "");
  EXPECT_EQ(list.refuses("fatek://10.0.0.6:500"),
            "this file allows only the targets fatek://10.0.0.5:*, tri-serial:/dev/ttyUSB0, not fatek://10.0.0.6:500");
  const HardwarePermission map = read("hardware:\n  targets: any\n  require_run: false\n");
  EXPECT_EQ(map.refuses("modbus://x:502"), "");
  EXPECT_FALSE(map.require_run);
  EXPECT_TRUE(read("hardware: true\n").require_run);
  try {
    read("hardware: {targets: [], rn: 1}\n");
    FAIL() << "no error";
  } catch (const SourceError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u);
    EXPECT_EQ(e.diagnostics()[0].where.line, 2);
    EXPECT_NE(e.diagnostics()[0].message.find("unknown key"), std::string::npos) << e.what();
  }
}

TEST(WallClockTarget, ASetOfAnInputForcesItOtherSetsWriteAndReleaseAllFreesOnlyWhatWasForced) {
  MemoryPlc m;
  m.plc.force(parse_address("M5"), ForceAction::Disable);  // someone else's force, not the case's
  const Case c = first_case("cases: [{name: a, steps: [{expect: motor}]}]\n");
  WallClockOptions o;
  o.wait = [](std::chrono::microseconds) { return false; };
  WallClockTarget t(m, config(), c, o);
  t.begin();
  auto value = [](double n) {
    Value v;
    v.number = n;
    v.text = std::to_string(n);
    return v;
  };
  t.set(parse_probe("part"), value(1));
  t.set(parse_probe("R7"), value(-2));
  t.force(parse_probe("motor"), true);
  EXPECT_TRUE(m.disabled("X3"));
  EXPECT_EQ(m.value("X3"), 1u);
  EXPECT_FALSE(m.disabled("X0"));
  EXPECT_EQ(m.value("R7"), 0xFFFEu);
  EXPECT_TRUE(m.disabled("Y0"));
  t.release(nullptr);
  EXPECT_FALSE(m.disabled("Y0"));  // the force step's point
  EXPECT_TRUE(m.disabled("X3"));   // the input the set holds stays held
  EXPECT_TRUE(m.disabled("M5"));   // and so does a force the case did not make
  EXPECT_THROW(t.simulate(nullptr), Error);
  EXPECT_EQ(t.touched().size(), 3u);
  EXPECT_EQ(t.check(parse_probe("F3"), false), "F3: F3 is not on this PLC");
  EXPECT_NE(t.check(parse_probe("counter.belt"), false).find("is read by its addresses and signals only"),
            std::string::npos);
}

TEST(WallClockTarget, APollReadsEveryAddressTheCaseReadsAndAStopEndsTheScan) {
  MemoryPlc m;
  m.plc.write(parse_address("Y0"), {1});
  const Case c = first_case("properties: [{never: latch}]\ncases: [{name: a, steps: [{expect: motor and R3 == 0}]}]\n");
  bool stop = false;
  WallClockOptions o;
  o.wait = [&](std::chrono::microseconds) { return stop; };
  o.why_stopped = [] { return std::string("stopped by SIGINT"); };
  WallClockTarget t(m, config(), c, o);
  EXPECT_EQ(t.polled_addresses().size(), 3u);  // Y0, R3 and the property's M0
  t.begin();
  EXPECT_EQ(m.reads, 1u);  // the first poll (the case touches nothing: nothing to read before it)
  EXPECT_EQ(t.read(parse_probe("motor")).text, "ON");
  t.scan(5000);
  EXPECT_GE(t.scanned_at(5000), 5000u);
  EXPECT_EQ(t.polls(), 2u);
  stop = true;
  try {
    t.scan(10000);
    FAIL() << "no stop";
  } catch (const Stopped& e) {
    EXPECT_NE(std::string(e.what()).find("stopped by SIGINT at "), std::string::npos) << e.what();
  }
  m.fail_next = 1;
  stop = false;
  try {
    t.scan(10000);
    FAIL() << "no link failure";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the link to the PLC in memory failed polling at "), std::string::npos)
        << e.what();
  }
}

TEST(Resolution, APollEveryRoundTripInWholeMillisecondsPlusTheScan) {
  MemoryPlc m;
  const Resolution r = measure_resolution(m, {parse_address("R0")}, 1000, 5);
  EXPECT_EQ(r.polls, 5u);
  EXPECT_EQ(m.reads, 6u);  // one to connect, then the five measured
  EXPECT_EQ(r.period_us % 1000, 0u);
  EXPECT_GE(r.period_us, kMinPollPeriodUs);
  EXPECT_EQ(r.us(), r.period_us + r.round_trip_us + 1000);
  EXPECT_EQ(wall_time(3100), "3.1 ms");
  EXPECT_EQ(wall_time(2000), "2 ms");
  EXPECT_EQ(wall_time(1102068), "1.102 s");
}

namespace {

// A cell whose Y0 turns on at 15 ms, seen by polls that come 20 ms late.
class LateTarget : public Target {
 public:
  uint64_t period_us() const override { return 10000; }
  void scan(uint64_t t_us) override { at_ = t_us + 20000; }
  uint64_t scanned_at(uint64_t) const override { return at_; }
  std::string check(const Probe&, bool) override { return ""; }
  Reading read(const Probe& p) override { return address_reading(parse_address(p.name), at_ >= 15000, p.format); }
  void set(const Probe&, const Value&) override {}
  void write(const Probe&, const Value&) override {}
  void force(const Probe&, bool) override {}
  void release(const Probe*) override {}
  void simulate(const Probe*) override {}
  std::string fault() override { return ""; }

 private:
  uint64_t at_ = 0;
};

}  // namespace

TEST(RunnerOnAWallClock, TimeFollowsTheTargetAndASightAfterTheWindowFailsIt) {
  // The first poll, due at 0, goes out at 20 ms and sees Y0 on: inside a window of 40 ms,
  // after one of 10 ms (which the scan due at 0 would have passed).
  LateTarget t;
  CaseResult ok = run_case(first_case("cases: [{name: a, steps: [{expect: Y0, within: 40ms}]}]\n"), t);
  EXPECT_TRUE(ok.passed) << ok.failure;
  EXPECT_EQ(ok.virtual_us, 20000u);
  LateTarget late;
  CaseResult r = run_case(first_case("cases: [{name: a, steps: [{expect: Y0, within: 10ms}]}]\n"), late);
  EXPECT_FALSE(r.passed);
  EXPECT_EQ(r.failure, "/d/s.yaml:2: expect Y0 within 0.010 s: held only at 0.020 s (0.020 s in, after the window): Y0 is ON");
  LateTarget seq;
  r = run_case(first_case("cases: [{name: a, steps: [{expect_sequence: [{that: Y0, within: 10ms}]}]}]\n"), seq);
  EXPECT_FALSE(r.passed);
  EXPECT_NE(r.failure.find("happened 0.020 s after the start of the sequence, after the latest 0.010 s"),
            std::string::npos)
      << r.failure;
}

namespace {

// M0 goes off at 10 ms; Y0, read from an older message, is seen off only at 35 ms: "Y0 and
// not M0" holds for 25 ms of readings without ever holding in the PLC. spread: what the
// target says of its readings' spread.
class SkewedTarget : public Target {
 public:
  explicit SkewedTarget(uint64_t spread) : spread_(spread) {}
  uint64_t period_us() const override { return 5000; }
  void scan(uint64_t t_us) override { at_ = t_us; }
  std::string check(const Probe&, bool) override { return ""; }
  Reading read(const Probe& p) override {
    const bool on = p.name == "M0" ? at_ < 10000 : at_ < 35000;
    return address_reading(parse_address(p.name), on, p.format);
  }
  void set(const Probe&, const Value&) override {}
  void write(const Probe&, const Value&) override {}
  void force(const Probe&, bool) override {}
  void release(const Probe*) override {}
  void simulate(const Probe*) override {}
  std::string fault() override { return ""; }
  uint64_t spread_us() override { return spread_; }

 private:
  uint64_t spread_, at_ = 0;
};

}  // namespace

TEST(RunnerOnAWallClock, AViolationNoLongerThanTheReadingsSpreadIsNotProof) {
  const std::string file =
      "properties:\n  - {never: Y0 and not M0, within: 5ms}\n"
      "cases: [{name: a, steps: [{after: 60ms}]}]\n";
  const Scenario sc = parse_scenario("cell: t.yaml\n" + file, "/d/s.yaml");
  const Case& c = sc.cases.at(0);
  SkewedTarget wide(30000);  // the run has seen messages 30 ms apart
  CaseResult ok = run_case(c, wide);
  EXPECT_TRUE(ok.passed) << ok.failure;
  SkewedTarget narrow(10000);
  CaseResult r = run_case(c, narrow);
  ASSERT_FALSE(r.passed);
  EXPECT_NE(r.failure.find("property never: Y0 and not M0 violated for longer than 0.010 s, the spread of the values "
                           "read so far in the run, (since 0.010 s)"),
            std::string::npos)
      << r.failure;
  SkewedTarget none(0);  // one instant: the property's own grace
  r = run_case(c, none);
  ASSERT_FALSE(r.passed);
  EXPECT_NE(r.failure.find("violated for longer than 0.005 s (since 0.010 s)"), std::string::npos) << r.failure;
}
