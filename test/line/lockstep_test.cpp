// Every example line's scenario gives every case the same verdict with its cells in
// lockstep (docs/native-engine.md, "Lockstep") as on the native engine, as the lone cells'
// scenarios do (test/scenario/lockstep_test.cpp): the wires drive both halves of each cell.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "plc_cell/line/line_target.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/scenario_file.h"

namespace plc_cell {
namespace {

namespace fs = std::filesystem;

scenario::CaseResult run_on(const scenario::Scenario& sc, const scenario::Case& c, const char* engine) {
  line::LineTarget t(sc.line, {{"", "engine", {engine}, "--engine"}});
  return scenario::run_case(c, t);
}

TEST(LineLockstep, EveryExampleLineScenarioGivesTheSameVerdictsInLockstep) {
  size_t cases = 0;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(PLC_CELL_SOURCE_DIR) / "examples")) {
    if (e.path().filename().string().find(".scenario.yaml") == std::string::npos) continue;
    const scenario::Scenario sc = scenario::load_scenario(e.path().string());
    if (sc.line.empty()) continue;
    for (const scenario::Case& c : sc.cases) {
      SCOPED_TRACE(e.path().filename().string() + ": " + c.name);
      const scenario::CaseResult native = run_on(sc, c, "native");
      const scenario::CaseResult lockstep = run_on(sc, c, "lockstep");
      EXPECT_TRUE(native.passed) << native.failure;
      EXPECT_EQ(lockstep.passed, native.passed) << lockstep.failure << "\n" << lockstep.details;
      EXPECT_EQ(lockstep.failure, native.failure);
      ++cases;
    }
  }
  EXPECT_GE(cases, 7u);  // examples/line/line.scenario.yaml at the time of writing
}

}  // namespace
}  // namespace plc_cell
