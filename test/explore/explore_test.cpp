// plc_cell explore: random runs within the declared domains, the same for the same seed;
// the shrinker's minimal run; the broken example found, shrunk to a few steps and its case
// reproducing the violation; the demo's properties holding over its exploration.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "../core/run_tool.h"
#include "../core/tool_text.h"
#include "plc_cell/explore/case_writer.h"
#include "plc_cell/explore/explorer.h"
#include "plc_cell/scenario/scenario_file.h"

using namespace plc_cell;
using namespace plc_cell::explore;
using plc_cell::testing::has;
using plc_cell::testing::run_tool;
using plc_cell::testing::slurp;
using plc_cell::testing::ToolResult;

namespace {

const std::string kSrc = PLC_CELL_SOURCE_DIR;

scenario::ExploreSpec spec() {
  const scenario::Scenario sc = scenario::parse_scenario(
      "cell: c.yaml\nexplore:\n  run: 10s\n  inputs:\n"
      "    X0: {hold: [50ms, 1s]}\n"
      "    R100: {values: [-5, 20], hold: [200ms, 2s]}\n",
      "/d/s.yaml");
  return sc.explore;
}

size_t count(const std::string& s, const std::string& part) {
  size_t n = 0;
  for (size_t p = s.find(part); p != std::string::npos; p = s.find(part, p + 1)) ++n;
  return n;
}

}  // namespace

TEST(Explore, RandomRunsKeepToTheDomainsAndDependOnTheSeedAlone) {
  const scenario::ExploreSpec s = spec();
  EXPECT_EQ(s.budget_us, 100000000u);  // ten runs by default
  const InputRun a = random_run(s, 7, 1000), b = random_run(s, 7, 1000), c = random_run(s, 8, 1000);
  EXPECT_EQ(a.changes, b.changes);
  EXPECT_NE(a.changes, c.changes);
  EXPECT_TRUE(respects_domains(s, a));
  EXPECT_GT(a.changes.size(), 10u);
  for (const Change& ch : a.changes) {
    EXPECT_EQ(ch.t_us % 1000, 0u);  // on the scan grid
    EXPECT_LT(ch.t_us, s.run_us);
    if (ch.input == 1) EXPECT_TRUE(ch.value >= -5 && ch.value <= 20) << ch.value;
  }
  InputRun too_short = a;
  too_short.changes = {{20000, 0, 1}};  // 20 ms: below X0's shortest hold of 50 ms
  EXPECT_FALSE(respects_domains(s, too_short));
}

TEST(Explore, TheShrinkerFindsTheSmallestRunThatStillFails) {
  const scenario::ExploreSpec s = spec();
  // Fails (as one property) when R100 has been above 3 while X0 is on; at the scan after.
  const Runner runner = [](const InputRun& run) {
    scenario::CaseResult r;
    double x0 = 0, r100 = -5;
    for (const Change& ch : run.changes) {
      (ch.input == 0 ? x0 : r100) = ch.value;
      if (x0 == 1 && r100 > 3) {
        r.failure = "/d/s.yaml:3: property never: X0 and R100 > 3 violated";
        r.virtual_us = ch.t_us + 1000;
        return r;
      }
    }
    r.passed = true;
    r.virtual_us = run.end_us;
    return r;
  };
  const InputRun start = random_run(s, 3, 1000);
  ASSERT_FALSE(runner(start).passed);
  uint64_t runs = 0;
  std::string failure;
  const InputRun small = shrink(s, start, runner, 1000, kMaxShrinkRuns, &runs, &failure);
  // Two changes at the earliest each domain allows, R100 at the simplest value above 3.
  ASSERT_EQ(small.changes.size(), 2u);
  EXPECT_EQ(small.changes[0], (Change{50000, 0, 1}));
  EXPECT_EQ(small.changes[1], (Change{200000, 1, 4}));
  EXPECT_EQ(small.end_us, 201000u);
  EXPECT_EQ(failure, "/d/s.yaml:3: property never: X0 and R100 > 3 violated");
  EXPECT_LT(runs, kMaxShrinkRuns);
}

TEST(Explore, TheBrokenExampleIsFoundShrunkAndItsCaseReproducesTheViolation) {
  const std::string out = ::testing::TempDir() + "/explore_broken.scenario.yaml";
  const std::string file = kSrc + "/examples/conveyor/broken_interlock.explore.yaml";
  const ToolResult r = run_tool("explore " + file + " --out " + out);
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(has(r.out, "property always: pick_request -> not conveyor_run violated")) << r.out;
  const std::string written = slurp(out);
  // A case of a few steps: the first set, at most three changes, the end.
  EXPECT_LE(count(written, "      - "), 5u) << written;
  const ToolResult again = run_tool("test " + out);
  EXPECT_EQ(again.status, 1) << again.out;
  EXPECT_TRUE(has(again.out, out + ":7: property always: pick_request -> not conveyor_run violated: "
                             "pick_request (Y2) is ON; conveyor_run (Y0) is ON")) << again.out;
  // The same seed, the same case, byte for byte.
  const std::string out2 = ::testing::TempDir() + "/explore_broken2.scenario.yaml";
  EXPECT_EQ(run_tool("explore " + file + " --out " + out2).status, 1);
  EXPECT_EQ(slurp(out2), written);
  // Another seed explores other runs, and finds the slip as well.
  EXPECT_EQ(run_tool("explore " + file + " --seed 5 --out " + out2).status, 1);
}

TEST(Explore, TheDemosPropertiesHoldOverItsExploration) {
  const ToolResult r = run_tool("explore " + kSrc + "/examples/conveyor/conveyor.scenario.yaml");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_TRUE(has(r.out, "seed 1, 10 run(s), 200.000 s of virtual time\nno property violated\n")) << r.out;
}

TEST(Explore, ErrorsBeforeAnyRun) {
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/explore_bad.yaml") << "cell: " << kSrc << "/examples/conveyor/conveyor.yaml\n"
                                           << "explore:\n  inputs:\n    start_buton: {hold: [50ms, 1s]}\n"
                                              "    part_present: {values: [0, 2], hold: [50ms, 1s]}\n"
                                              "    Y0: {hold: [1s, 50ms]}\n";
  const ToolResult r = run_tool("explore " + dir + "/explore_bad.yaml");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(has(r.out, "explore_bad.yaml:4: error: key 'explore.inputs.start_buton': 'start_buton' is neither a signal"))
      << r.out;
  EXPECT_TRUE(has(r.out, "explore_bad.yaml:5: error: key 'explore.inputs.part_present': part_present: value 2 out of range 0..1"))
      << r.out;
  EXPECT_TRUE(has(r.out, "explore_bad.yaml:6:16: error: key 'explore.inputs.Y0.hold': the shortest hold must be above 0"))
      << r.out;
  std::ofstream(dir + "/explore_none.yaml") << "cell: " << kSrc << "/examples/conveyor/conveyor.yaml\n"
                                            << "cases:\n  - {name: a, steps: [{after: 1s}]}\n";
  const ToolResult none = run_tool("explore " + dir + "/explore_none.yaml");
  EXPECT_EQ(none.status, 1);
  EXPECT_TRUE(has(none.out, "explore_none.yaml: error: no 'explore:' section")) << none.out;
}

TEST(Explore, DurationsAsTheScenarioFilesWriteThem) {
  EXPECT_EQ(duration_text(1000), "1ms");
  EXPECT_EQ(duration_text(1250000), "1.25s");
  EXPECT_EQ(duration_text(2000000), "2s");
  EXPECT_EQ(duration_text(1500), "1500us");
}
