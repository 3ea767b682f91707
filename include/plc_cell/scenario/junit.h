#pragma once
// A run's results as JUnit XML, as Jenkins, GitLab and catkin's run_tests read it: one
// testsuite per scenario file, one testcase per case. The time attributes are virtual
// seconds, so that the same run writes the same file.
#include <ostream>
#include <vector>

#include "plc_cell/scenario/runner.h"

namespace plc_cell {
namespace scenario {

void write_junit(const std::vector<CaseResult>& results, std::ostream& out);

}  // namespace scenario
}  // namespace plc_cell
