#pragma once
// The monitor's JSON forms of what a Source gives (docs/monitor-api.md).
#include <string>

#include <nlohmann/json.hpp>

#include "plc_cell/monitor/source.h"

namespace plc_cell {
namespace monitor {

// "run", "stop", or "unknown" where the source cannot tell (Frame::mode_known).
const char* mode_text(RunMode m, bool known = true);
nlohmann::json status_json(const CellStatus& s);
// j as text; invalid UTF-8 (a hostile name echoed back) is replaced, never thrown on.
std::string dump(const nlohmann::json& j);
// {"error": why}: every refusal's body.
std::string error_body(const std::string& why);

}  // namespace monitor
}  // namespace plc_cell
