#pragma once
// Runs one test case on a target, scan by scan in virtual time, and says how it went.
// A failure names the step (file:line), what was expected, the actual values, the virtual
// time, and the last changes of every probe the expectation reads.
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/core/error.h"
#include "plc_cell/scenario/scenario.h"
#include "plc_cell/scenario/target.h"

namespace plc_cell {
namespace scenario {

struct CaseResult {
  std::string name;
  std::string file;
  int line = 0;
  bool passed = false;
  uint64_t virtual_us = 0;  // the case's end (or its failure's) virtual time
  uint64_t scans = 0;
  std::string failure;       // one line: "conveyor.scenario.yaml:25: expect Y2 == 1 within 1.5 s"
  std::string details;       // the actual values and the last changes, several lines
};

// How many changes per probe a failure report lists.
constexpr size_t kHistoryDepth = 5;

CaseResult run_case(const Case& c, Target& target);

// Every probe the steps of c read or drive, each checked on the target: an error per
// unknown name at its step's line (none: all known).
std::vector<Diagnostic> check_case(const Case& c, Target& target);

// "2.500 s"
std::string format_time(uint64_t us);

}  // namespace scenario
}  // namespace plc_cell
