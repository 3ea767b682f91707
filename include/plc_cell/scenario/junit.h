#pragma once
// A run's results as JUnit XML, as Jenkins, GitLab and catkin's run_tests read it: one
// testsuite per scenario file, one testcase per case. The time attributes are virtual
// seconds, so that the same run writes the same file; on a PLC over a link (run.target:
// "fatek://10.0.0.5:500"), wall-clock seconds, and the target is in every suite's name.
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "plc_cell/scenario/runner.h"

namespace plc_cell {
namespace scenario {

// A run on a PLC over a link: its target, and what every suite lists as its properties
// (the resolution, the windows widened, what was restored).
struct JUnitRun {
  std::string target;
  std::vector<std::pair<std::string, std::string>> properties;
};

void write_junit(const std::vector<CaseResult>& results, std::ostream& out, const JUnitRun& run = {});

}  // namespace scenario
}  // namespace plc_cell
