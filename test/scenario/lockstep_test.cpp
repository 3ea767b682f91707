// Scenario steps drive both halves of a lockstep cell (docs/native-engine.md, "Lockstep"):
// every example scenario gives every case the same verdict in lockstep as on the native
// engine, and no case ends on a lockstep difference, whether its steps set terminals, write
// or force memory, give inputs back to the simulation or drive an extension's stimulus (a
// temperature channel, an analog input), which acts on the extension itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "plc_cell/scenario/cell_target.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/scenario_file.h"

using namespace plc_cell;
namespace fs = std::filesystem;

namespace {

scenario::CaseResult run_on(const scenario::Scenario& sc, const scenario::Case& c, const char* engine) {
  scenario::CellTarget t(sc.cell, sc.program, {{"", "engine", {engine}, "--engine"}});
  return scenario::run_case(c, t);
}

}  // namespace

TEST(ScenarioLockstep, EveryExampleScenarioGivesTheSameVerdictsInLockstep) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(PLC_CELL_SOURCE_DIR) / "examples")) {
    const std::string name = e.path().filename().string();
    if (name.find(".scenario.yaml") != std::string::npos || name.find(".fails.yaml") != std::string::npos)
      files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 6u);  // at the time of writing
  int stimuli = 0;
  for (const fs::path& f : files) {
    const scenario::Scenario sc = scenario::load_scenario(f.string());
    if (!sc.line.empty()) continue;  // a line's: test/line/lockstep_test.cpp runs them so
    for (const scenario::Case& c : sc.cases) {
      SCOPED_TRACE(f.filename().string() + ": " + c.name);
      for (const auto& s : c.steps)
        for (const auto& a : s.assignments) stimuli += a.value.has_unit;
      const scenario::CaseResult native = run_on(sc, c, "native");
      const scenario::CaseResult lockstep = run_on(sc, c, "lockstep");
      EXPECT_EQ(lockstep.passed, native.passed) << lockstep.failure << "\n" << lockstep.details;
      EXPECT_EQ(lockstep.failure.find("lockstep: "), std::string::npos) << lockstep.failure;
      EXPECT_EQ(lockstep.failure, native.failure);
    }
  }
  EXPECT_GT(stimuli, 0);  // a temperature or analog stimulus among the steps
}
