// A made-up extension (test/extension/ticker_extension.h) plugs into a cell with no change
// to any other file: its section is read, its FUN runs, and its probe is read by a scenario
// through the cell in process, as `plc_cell test` reads it.
#include <gtest/gtest.h>

#include "../extension/ticker_extension.h"
#include "scenario_fixture.h"

using namespace plc_cell;

namespace {

constexpr const char* kTickerProgram = "ORG M1925\nFUN 901\nEND\n";  // M1925: always on

TEST(MadeUpExtension, ItsProbeIsReadByAScenario) {
  ticker::Registration registered;
  plc_cell::testing::ScenarioCell cell("ticker", kTickerProgram, "ticker: {start: 5}\n");
  // 5 from the YAML, then one per scan: the scan at 9 ms is the 10th.
  const scenario::CaseResult r = cell.run("      - at: 9ms\n        expect: ticker.count == 15\n");
  EXPECT_TRUE(r.passed) << r.failure << "\n" << r.details;
  const scenario::CaseResult wrong = cell.run("      - at: 9ms\n        expect: ticker.count == 14\n");
  EXPECT_FALSE(wrong.passed);
  EXPECT_NE(wrong.details.find("15"), std::string::npos) << wrong.details;
}

TEST(MadeUpExtension, ItsTargetCheckSaysWhatIsMissing) {
  ticker::Registration registered;
  plc_cell::testing::ScenarioCell cell("ticker_check", kTickerProgram, "ticker: {start: 0}\n");
  const scenario::Scenario sc = cell.parse("      - expect: ticker.count == 0\n");
  scenario::CellTarget t(sc.cell, sc.program);
  EXPECT_EQ(t.check(scenario::parse_probe("ticker.speed"), false),
            "ticker.speed: the ticker has ticker.count and ticker.step only");
  EXPECT_EQ(t.check(scenario::parse_probe("ticker.count"), false), "");
  EXPECT_EQ(t.check(scenario::parse_probe("ticker.count"), true), "ticker.count: it is read, not driven");
}

// The extension declares the stimuli its probes take (ticks, kticks) as it declares its
// probes: a step writes them, the scenario layer reads them, the extension is driven.
TEST(MadeUpExtension, ItsOwnStimulusParsesAndDrives) {
  ticker::Registration registered;
  plc_cell::testing::ScenarioCell cell("ticker_stimulus", kTickerProgram, "ticker: {start: 0}\n");
  // The scans at 0..5 ms add 1 each; from the next one on, 2 kticks = 2000 each: at 9 ms,
  // 6 + 4 x 2000.
  const scenario::CaseResult r = cell.run(
      "      - at: 5ms\n        set: {ticker.step: 2 kticks}\n"
      "      - at: 9ms\n        expect: ticker.count == 8006\n");
  EXPECT_TRUE(r.passed) << r.failure << "\n" << r.details;
  const scenario::Scenario sc = cell.parse("      - set: {ticker.step: 3 ticks}\n");
  EXPECT_EQ(sc.cases.at(0).steps.at(0).assignments.at(0).value.number, 3);
  EXPECT_EQ(sc.cases.at(0).steps.at(0).assignments.at(0).value.unit, "ticks");
  // Its own units only, and named as it declared them.
  try {
    cell.parse("      - set: {ticker.step: 2 mV}\n");
    FAIL() << "2 mV parsed";
  } catch (const SourceError& e) {
    EXPECT_NE(std::string(e.what()).find("'cases[0].steps[0].set.ticker.step': a ticker takes ticks or kticks, not mV"),
              std::string::npos)
        << e.what();
  }
}

TEST(MadeUpExtension, UnregisteredItIsNeitherASectionNorAProbe) {
  {
    ticker::Registration registered;
  }
  EXPECT_THROW(scenario::parse_probe("ticker.count"), Error);
  plc_cell::testing::ScenarioCell cell("ticker_gone", "ORG M1925\nOUT Y0\nEND\n", "ticker: {start: 0}\n");
  EXPECT_THROW(scenario::CellTarget(cell.dir() + "/cell.yaml", ""), Error);  // ticker: is no section
}

}  // namespace
