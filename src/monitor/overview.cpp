#include "overview.h"

#include "json_views.h"
#include "plc_cell/core/error.h"
#include "static_files.h"

namespace plc_cell {
namespace monitor {
namespace {

ApiReply overview_reply(const nlohmann::json& j) { return {200, "application/json", dump(j)}; }

nlohmann::json violation_json(const PropertyStatus& p) {
  nlohmann::json values = nlohmann::json::array();
  for (const auto& v : p.last_values) values.push_back({{"name", v.name}, {"value", v.value}});
  return {{"text", p.text},        {"where", p.where},
          {"begin_us", p.last_begin_us}, {"duration_us", p.last_duration_us},
          {"ongoing", p.last_ongoing}, {"values", values}};
}

// Each property's state at the report's instant, and the one whose last violation began
// last (the first listed of those that began at one instant).
void add_properties(const PropertyReport& r, nlohmann::json* out) {
  nlohmann::json list = nlohmann::json::array(), last = nullptr;
  const PropertyStatus* latest = nullptr;
  for (const auto& p : r.properties) {
    nlohmann::json j = {{"text", p.text}, {"where", p.where}, {"within_us", p.within_us},
                        {"state", !r.evaluated ? "not evaluated yet" : p.violated ? "violated" : "holding"},
                        {"since_us", p.violated ? nlohmann::json(p.since_us) : nlohmann::json(nullptr)},
                        {"violations", p.violations},
                        {"last", p.violations ? violation_json(p) : nlohmann::json(nullptr)}};
    list.push_back(j);
    if (p.violations && (!latest || p.last_begin_us > latest->last_begin_us)) latest = &p;
  }
  if (latest) last = violation_json(*latest);
  (*out)["properties"] = list;
  (*out)["last_violated"] = last;
  (*out)["properties_t_us"] = r.evaluated ? nlohmann::json(r.t_us) : nlohmann::json(nullptr);
  (*out)["properties_note"] = std::to_string(r.properties.size()) + (r.properties.size() == 1 ? " property" : " properties") +
                              " of " + r.source + ", " + r.how;
}

}  // namespace

ApiReply Overview::get(const std::string& path) const {
  if (path == "/api/overview") return overview_reply(json());
  if (path == "/api/session") {
    nlohmann::json cells = nlohmann::json::array();
    for (size_t i = 0; i < set_.size(); ++i) cells.push_back(set_.name(i));
    return overview_reply({{"token", apis_.front()->token()},
                           {"writable", settings_.writable.describe()},
                           {"source", set_.title()},
                           {"kind", kind_text(set_.source(0).kind())},
                           {"cells", cells}});
  }
  // The overview's page (/, /index.html): a file of the page's folder.
  const auto file = static_file("/assets/overview.html",
                                settings_.asset_root.empty() ? default_asset_root() : settings_.asset_root,
                                settings_.vendor_root);
  return {file.status, file.type, file.body};
}

nlohmann::json Overview::json() const {
  nlohmann::json cells = nlohmann::json::array(), wires = nlohmann::json::array();
  for (size_t i = 0; i < set_.size(); ++i) cells.push_back(cell_json(i));
  for (const auto& w : set_.wires()) wires.push_back(wire_json(w));
  nlohmann::json o = {{"title", set_.title()},
                      {"kind", kind_text(set_.source(0).kind())},
                      {"cells", cells},
                      {"wires", wires}};
  if (const PropertyBoard* board = set_.properties()) {
    // A recording's at its replay cursor, which every cell of the set shares.
    Replay* replay = set_.source(0).replay();
    add_properties(replay ? board->report_at(replay->cursor_us()) : board->report(), &o);
    return o;
  }
  // No properties given (docs/monitor.md, "Properties"): it claims no violation.
  o["properties"] = nullptr;
  o["last_violated"] = nullptr;
  o["properties_t_us"] = nullptr;
  o["properties_note"] = "no properties watched";
  return o;
}

// The cell's own status (what its Status tab shows), read now, and the instant it is of.
nlohmann::json Overview::cell_json(size_t i) const {
  Api& api = *apis_[i];
  nlohmann::json c = {{"name", set_.name(i)},
                      {"page", "/cell/" + set_.name(i) + "/"},
                      {"source", api.source().describe()},
                      {"stale", nullptr}};
  try {
    const nlohmann::json s = api.status_now();
    for (const char* k : {"mode", "mode_switchable", "mode_refusal", "engine", "scan", "scan_note", "note", "forced",
                          "forced_note"})
      c[k] = s[k];
    c["faults"] = nlohmann::json::array();
    for (const auto& e : s["extensions"])
      if (e["level"] != "ok") c["faults"].push_back({{"name", e["name"]}, {"level", e["level"]}, {"message", e["message"]}});
    c["t_us"] = api.source().read({}).t_us;
  } catch (const std::exception& e) {
    // Nothing of it can be said now: no mode, no figures, the reason.
    c["mode"] = "unknown";
    c["stale"] = {{"error", e.what()}};
  }
  return c;
}

// Both ends read now: the sink's value lags the source's by the wire's delay.
nlohmann::json Overview::wire_json(const SetWire& w) const {
  nlohmann::json j = {{"from", w.from}, {"to", w.to}, {"text", w.text},
                      {"from_value", nullptr}, {"to_value", nullptr}, {"error", ""}};
  try {
    for (const auto& [end, key] : {std::make_pair(&w.from, "from_value"), std::make_pair(&w.to, "to_value")}) {
      Located at;
      if (!set_.locate(*end, &at)) throw Error(*end + ": no such cell in this monitor (cells: " + set_.names() + ")");
      j[key] = set_.source(at.cell).read({at.address}).values.at(0);
    }
  } catch (const std::exception& e) {
    j["error"] = e.what();
  }
  return j;
}

}  // namespace monitor
}  // namespace plc_cell
