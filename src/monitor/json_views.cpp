#include "json_views.h"

#include "plc_cell/core/scan_health.h"

namespace plc_cell {
namespace monitor {
namespace {

const char* level_text(ExtensionStatus::Level l) {
  switch (l) {
    case ExtensionStatus::Level::Ok: return "ok";
    case ExtensionStatus::Level::Warn: return "warn";
    case ExtensionStatus::Level::Error: return "error";
  }
  return "error";
}

// A duration never measured (a scan in virtual time has no cycle time) is null, not 0.
nlohmann::json avg_json(const DurationStats& d) { return d.count ? nlohmann::json(uint64_t(d.avg_ns())) : nullptr; }
nlohmann::json max_json(const DurationStats& d) { return d.count ? nlohmann::json(d.max_ns) : nullptr; }

nlohmann::json scan_json(const ScanStats& s) {
  return {{"scans", s.scans},
          {"cycle_avg_ns", avg_json(s.cycle)},
          {"cycle_max_ns", max_json(s.cycle)},
          {"wake_avg_ns", avg_json(s.wake_latency)},
          {"wake_max_ns", max_json(s.wake_latency)},
          {"overruns", s.overruns},
          {"overruns_off_cpu", s.overruns_off_cpu}};
}

}  // namespace

const char* mode_text(RunMode m, bool known) { return !known ? "unknown" : m == RunMode::Run ? "run" : "stop"; }

nlohmann::json status_json(const CellStatus& s) {
  nlohmann::json j = {{"mode", mode_text(s.mode, s.mode_known)},
                      {"mode_switchable", s.mode_switchable},
                      {"engine", s.engine},
                      {"note", s.note}};
  // A source without the PLC's own scan figures gives none rather than figures of something else.
  if (s.scan_note.empty()) j["scan"] = scan_json(s.scan);
  else j["scan"] = nullptr;
  j["scan_note"] = s.scan_note;
  j["forced_note"] = s.forced_note;
  j["extensions"] = nlohmann::json::array();
  for (const auto& e : s.extensions) {
    nlohmann::json values = nlohmann::json::array();
    for (const auto& kv : e.values) values.push_back({kv.first, kv.second});
    j["extensions"].push_back(
        {{"name", e.name}, {"level", level_text(e.level)}, {"message", e.message}, {"values", values}});
  }
  j["servers"] = nlohmann::json::array();
  for (const auto& [name, st] : s.servers)
    j["servers"].push_back({{"name", name},
                            {"running", st.running},
                            {"requests", st.requests},
                            {"rejected", st.rejected},
                            {"connections", st.connections},
                            {"link_up", st.link_up},
                            {"last_error", st.last_error}});
  j["forced"] = nlohmann::json::array();
  for (const auto& a : s.forced) j["forced"].push_back(format_address(a));
  return j;
}

const char* kind_text(SourceKind k) {
  switch (k) {
    case SourceKind::Live: return "live";
    case SourceKind::Remote: return "remote";
    case SourceKind::Replay: return "replay";
  }
  return "remote";
}

std::string dump(const nlohmann::json& j) { return j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace); }

std::string error_body(const std::string& why) { return dump(nlohmann::json{{"error", why}}); }

}  // namespace monitor
}  // namespace plc_cell
