#pragma once
// The ladder and its power flow as the monitor's JSON (docs/ladder.md, docs/monitor-api.md).
#include <nlohmann/json.hpp>

#include "plc_cell/ladder/flow.h"
#include "plc_cell/ladder/layout.h"

namespace plc_cell {
namespace ladder {

nlohmann::json to_json(const Layout& layout);
nlohmann::json to_json(const Network& network);
nlohmann::json to_json(const Flow& flow);  // {"net": 0, "on": [0, 1, 10]}

}  // namespace ladder
}  // namespace plc_cell
