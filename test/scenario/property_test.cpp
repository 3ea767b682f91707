// Properties: checked after every scan of every case, with their grace time, and their
// errors at file:line (docs/testing-your-cell.md, "Properties").
#include <gtest/gtest.h>

#include "plc_cell/config/error_list.h"
#include "scenario_fixture.h"

using namespace plc_cell;
using namespace plc_cell::scenario;
using plc_cell::testing::ScenarioCell;

namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// The fixture's cell (Y0 follows X0; X1 held 0.5 s turns Y1 on) with properties and one case.
CaseResult run(const ScenarioCell& cell, const std::string& properties, const std::string& steps) {
  const Scenario sc = parse_scenario("cell: cell.yaml\nproperties:\n" + properties +
                                         "cases:\n  - name: c\n    steps:\n" + steps,
                                     cell.dir() + "/s.yaml");
  CellTarget t(sc.cell, sc.program);
  const auto errors = check_case(sc.cases.at(0), t);
  EXPECT_TRUE(errors.empty()) << errors.at(0).to_string();
  return run_case(sc.cases.at(0), t);
}

}  // namespace

TEST(ScenarioProperties, NeverFailsAtTheFirstScanWhereItsConditionHolds) {
  ScenarioCell cell("prop_never");
  // X0 and X1 from the scan at 0: Y0 at once, Y1 once T0's 0.5 s are up (the scan at 500 ms).
  const CaseResult r = run(cell, "  - never: motor and done\n",
                           "      - set: {start: on, hold: on}\n"
                           "      - after: 2s\n");
  ASSERT_FALSE(r.passed);
  EXPECT_TRUE(has(r.failure, "/s.yaml:3: property never: motor and done violated: motor (Y0) is ON, done (Y1) is ON"))
      << r.failure;
  EXPECT_EQ(r.virtual_us, 500000u);
  EXPECT_TRUE(has(r.details, "done (Y1):  initially OFF  0.500 s ON")) << r.details;
  // Without X0 the property holds in every scan of the 2 s.
  const CaseResult ok = run(cell, "  - never: motor and done\n",
                            "      - set: {hold: on}\n"
                            "      - after: 2s\n");
  EXPECT_TRUE(ok.passed) << ok.failure;
}

TEST(ScenarioProperties, AlwaysIsAnImplication) {
  ScenarioCell cell("prop_always");
  // "hold -> not done": violated from 500 ms while X1 stays on; X1 off first: never.
  const CaseResult bad = run(cell, "  - always: hold -> not done\n",
                             "      - set: {hold: on}\n"
                             "      - after: 1s\n");
  ASSERT_FALSE(bad.passed);
  EXPECT_TRUE(has(bad.failure, "property always: hold -> not done violated: hold (X1) is ON; done (Y1) is ON"))
      << bad.failure;
  EXPECT_EQ(bad.virtual_us, 500000u);
  const CaseResult ok = run(cell, "  - always: hold -> not done\n",
                            "      - pulse: {hold: 400ms}\n"
                            "      - after: 1s\n");
  EXPECT_TRUE(ok.passed) << ok.failure;
}

TEST(ScenarioProperties, WithinIsAGraceTime) {
  ScenarioCell cell("prop_within");
  // X1 held 700 ms from the scan at 0: Y1 is ON from 500 ms to 699 ms, 200 ms of violation.
  const std::string steps = "      - pulse: {hold: 700ms}\n      - after: 2s\n";
  const CaseResult ok = run(cell, "  - never: done\n    within: 200ms\n", steps);
  EXPECT_TRUE(ok.passed) << ok.failure;
  const CaseResult bad = run(cell, "  - never: done\n    within: 150ms\n", steps);
  ASSERT_FALSE(bad.passed);
  EXPECT_TRUE(has(bad.failure, "property never: done violated for longer than 0.150 s (since 0.500 s)")) << bad.failure;
  EXPECT_EQ(bad.virtual_us, 651000u);
}

TEST(ScenarioProperties, ErrorsAtTheirLines) {
  ScenarioCell cell("prop_errors");
  ErrorList errors;
  parse_scenario("cell: cell.yaml\nproperties:\n"
                 "  - never: Y0 -> Y1\n"
                 "  - always: Y0 =< 1\n"
                 "  - {never: Y0, always: Y1}\n"
                 "  - {always: Y0, within: soon}\n"
                 "  - always: -> Y1\n"
                 "cases:\n  - name: c\n    steps:\n      - after: 1s\n",
                 "/d/p.yaml", errors);
  std::vector<std::string> got;
  for (const auto& d : errors.diagnostics()) got.push_back(d.to_string());
  ASSERT_EQ(got.size(), 5u);
  EXPECT_TRUE(has(got[0], "/d/p.yaml:3:12: error: key 'properties[0].never': 'Y0 -> Y1': '->' goes with always")) << got[0];
  EXPECT_TRUE(has(got[1], "/d/p.yaml:4:13: error: key 'properties[1].always': 'Y0 =< 1': expected ==")) << got[1];
  EXPECT_TRUE(has(got[2], "/d/p.yaml:5:5: error: key 'properties[2]': a property has one of 'never' and 'always'")) << got[2];
  EXPECT_TRUE(has(got[3], "/d/p.yaml:6:26: error: key 'properties[3].within': bad duration 'soon'")) << got[3];
  EXPECT_TRUE(has(got[4], "/d/p.yaml:7:13: error: key 'properties[4].always': '-> Y1': nothing before '->'")) << got[4];
  // A name the cell does not have: at the property's line, before any case runs.
  const Scenario sc = parse_scenario("cell: cell.yaml\nproperties:\n  - never: motr\n"
                                     "cases:\n  - name: c\n    steps:\n      - after: 1s\n",
                                     cell.dir() + "/s.yaml");
  CellTarget t(sc.cell, sc.program);
  const auto unknown = check_case(sc.cases.at(0), t);
  ASSERT_EQ(unknown.size(), 1u);
  EXPECT_TRUE(has(unknown[0].to_string(), "/s.yaml:3: error: key 'never': 'motr' is neither a signal")) << unknown[0].to_string();
}
