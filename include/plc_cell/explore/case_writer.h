#pragma once
// A run written out as a scenario file that `plc_cell test` runs as it is: the cell and
// the program (or the line), the properties and one case whose steps replay the run.
#include <string>

#include "plc_cell/explore/input_run.h"

namespace plc_cell {
namespace explore {

// out_path: where the file goes (the cell and program are named relative to its folder).
// comment: lines put first, each as a YAML comment.
std::string case_file(const scenario::Scenario& sc, const InputRun& run, const std::string& name,
                      const std::string& out_path, const std::string& comment);

// "1.25s", "2s", "1500us": a time as the scenario files take it.
std::string duration_text(uint64_t us);

}  // namespace explore
}  // namespace plc_cell
