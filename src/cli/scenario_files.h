#pragma once
// What plc_cell test, explore and the mutation run share: the scenario files read and their
// names checked against their cells (or lines of cells) before anything runs, and the
// --engine option.
#include <optional>
#include <string>
#include <vector>

#include "args.h"
#include "plc_cell/core/scan_engine.h"
#include "fresh_target.h"
#include "plc_cell/scenario/cell_target.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace cli {

// Every file read, every name its steps, properties and explore inputs use checked on a
// fresh cell; false (with every error printed, sorted, and "TOOL: N error(s)...") if any.
bool load_scenarios(const std::vector<std::string>& paths, const std::string& tool,
                    std::vector<scenario::Scenario>* files);

// One line per case, "PASS  FILE: NAME  (TIME)", and a failure's report below it.
void print_result(const scenario::Scenario& sc, const scenario::CaseResult& r, const std::string& time);

// --engine, if given (UsageError when it names no engine).
std::optional<EngineChoice> engine_option(const Args& args);
// A fresh cell (or line) of sc for one case, on the engine asked for.
inline std::unique_ptr<FreshTarget> fresh_target(const scenario::Scenario& sc, std::optional<EngineChoice> engine) {
  return std::make_unique<FreshTarget>(sc, engine);
}

}  // namespace cli
}  // namespace plc_cell
