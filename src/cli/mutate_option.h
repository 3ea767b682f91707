#pragma once
// plc_cell test --mutate: the mutation run after the cases passed (src/mutation/).
#include <optional>
#include <string>
#include <vector>

#include "args.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace cli {

// Prints the report, writes --mutate-json; *html: the section for the coverage page.
// Options: --mutate-budget N, --jobs N (-j N), --mutate-json OUT.json.
void run_mutate(const Args& args, const std::vector<scenario::Scenario>& files, std::optional<EngineChoice> engine,
                std::string* html);

}  // namespace cli
}  // namespace plc_cell
