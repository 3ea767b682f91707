#include "plc_cell/config/program_changes.h"

namespace plc_cell {

const char* source_text(ChangeSource s) {
  switch (s) {
    case ChangeSource::Service: return "service";
    case ChangeSource::Page: return "page";
    case ChangeSource::File: return "file";
  }
  return "?";
}

nlohmann::json to_json(const GateResult& g) {
  nlohmann::json j{{"configured", g.configured}, {"passed", g.passed}, {"summary", g.summary},
                   {"report", g.report},         {"seconds", g.seconds}, {"hash", g.hash}};
  if (!g.since.empty()) j["since"] = g.since;
  return j;
}

nlohmann::json to_json(const ChangeOutcome& o) {
  nlohmann::json errors = nlohmann::json::array();
  for (const auto& e : o.errors) errors.push_back({{"line", e.line}, {"column", e.column}, {"message", e.message}});
  return {{"result", o.result},     {"why", o.why},           {"errors", errors},
          {"refusals", o.refusals}, {"gate", to_json(o.gate)}, {"old_hash", o.old_hash},
          {"new_hash", o.new_hash}, {"diff", o.diff},        {"swap_ms", o.swap_ms},
          {"instructions", o.instructions}, {"undo", o.undo}};
}

}  // namespace plc_cell
