#pragma once
// A cell written to a temporary folder, and its scenarios run in process.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "plc_cell/scenario/cell_target.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/scenario_file.h"

namespace plc_cell {
namespace testing {

// T0 has a 10 ms base: "TMR T0 50" is 0.5 s.
constexpr const char* kTestProgram =
    "ORG X0\nOUT Y0\n"        // Y0 follows X0
    "ORG X1\nTMR T0 50\n"     // X1 held 0.5 s
    "ORG T0\nOUT Y1\n"        // turns Y1 on
    "ORG X2\nOUT M5\n"
    "ORG M1925\nMOV S=R100 D=R101\n"
    "END\n";

class ScenarioCell {
 public:
  explicit ScenarioCell(const std::string& name, const std::string& program = kTestProgram,
                        const std::string& extra_yaml = "") {
    dir_ = ::testing::TempDir() + "/scenario_" + name;
    std::system(("mkdir -p " + dir_).c_str());
    std::ofstream(dir_ + "/cell.il") << program;
    std::ofstream(dir_ + "/cell.yaml") << "cell: {name: t, program: cell.il}\n"
                                          "plc: {scan_period: 0.001}\n"
                                          "signals: {start: X0, motor: Y0, hold: X1, done: Y1}\n"
                                       << extra_yaml;
  }
  const std::string& dir() const { return dir_; }

  // The scenario's steps under one case named "c" (a YAML list, indented by 6).
  scenario::Scenario parse(const std::string& steps) const {
    return scenario::parse_scenario("cell: cell.yaml\ncases:\n  - name: c\n    steps:\n" + steps, dir_ + "/s.yaml");
  }
  scenario::CaseResult run(const std::string& steps) const {
    const scenario::Scenario sc = parse(steps);
    scenario::CellTarget t(sc.cell, sc.program);
    const auto errors = scenario::check_case(sc.cases.at(0), t);
    EXPECT_TRUE(errors.empty()) << errors.at(0).to_string();
    return scenario::run_case(sc.cases.at(0), t);
  }

 private:
  std::string dir_;
};

}  // namespace testing
}  // namespace plc_cell
