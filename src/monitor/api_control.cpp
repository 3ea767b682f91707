// The API's POSTs: what changes the PLC (write, force, RUN/STOP) or the replay cursor.
// Each is checked whole before anything is done, and every one, accepted or refused, is
// logged to every page.
#include "api.h"
#include "feed.h"
#include "json_views.h"
#include "plc_cell/core/error.h"

namespace plc_cell {
namespace monitor {
namespace {

ApiReply ok_reply() { return {200, "application/json", "{\"ok\":true}"}; }

const nlohmann::json& field(const nlohmann::json& body, const std::string& key, const std::string& what) {
  if (!body.contains(key)) throw Error(what + ": no \"" + key + "\"");
  return body[key];
}

std::string text_field(const nlohmann::json& body, const std::string& key, const std::string& what) {
  const auto& v = field(body, key, what);
  if (!v.is_string()) throw Error(what + ": \"" + key + "\" must be a string");
  return v.get<std::string>();
}

// What a change the page asked for is called in the log: "write D0", "force Y0", "mode".
std::string change_name(const char* verb, const nlohmann::json& body, const char* key) {
  const auto it = body.find(key);
  return it != body.end() && it->is_string() ? std::string(verb) + " " + it->get<std::string>() : verb;
}

// The page's watch table, whose changes are events too: {"watch": ["D5", "tank_low"]}.
std::vector<Address> watched_addresses(const nlohmann::json& body, const ProgramView& program) {
  std::vector<Address> out;
  if (!body.contains("watch")) return out;
  const auto& w = body["watch"];
  if (!w.is_array() || w.size() > kMaxWatch)
    throw Error("replay: \"watch\" must be a list of up to " + std::to_string(kMaxWatch) + " names");
  for (const auto& name : w) {
    if (!name.is_string()) throw Error("replay: \"watch\" must be a list of names");
    out.push_back(resolve(name.get<std::string>(), program));
  }
  return out;
}

}  // namespace

uint32_t elements(const Address& a, uint32_t count) {
  uint32_t per = 1;
  if (is_discrete(a.area)) per = a.width == Width::Bit ? 1 : a.width == Width::Word ? 16 : 32;
  else if (a.width == Width::DWord && a.area != Area::RC) per = 2;
  return count * per;
}

std::string Api::cannot(Change c) const { return source_.refusal(c); }

std::string Api::cannot_write(const Address& a, uint32_t count) const {
  if (std::string why = cannot(Change::Write); !why.empty()) return why;
  return not_writable(a, elements(a, count));
}

std::string Api::cannot_force(const Address& a) const {
  if (a.width != Width::Bit || !is_discrete(a.area)) return format_address(a) + " is not a single discrete";
  if (std::string why = cannot(Change::Force); !why.empty()) return why;
  return not_writable(a, 1);
}

std::string Api::cannot_switch_mode() const {
  if (std::string why = cannot(Change::Mode); !why.empty()) return why;
  // RUN/STOP reaches every address: only a server writable everywhere switches it.
  if (!settings_.writable.everything()) return "RUN/STOP needs writable: all (writable: " + settings_.writable.describe() + ")";
  return "";
}

ApiReply Api::refuse_write(const std::string& what, const std::string& why) {
  log(what + " (refused: " + why + ")");
  return {403, "application/json", error_body(what + ": " + why)};
}

std::string Api::not_writable(const Address& a, uint32_t elements) const {
  if (settings_.writable.allows(a.area, a.index, elements)) return "";
  return format_address(a) + " is not writable (writable: " + settings_.writable.describe() + ")";
}

ApiReply Api::apply(const std::string& what, const std::string& refusal, const std::function<void()>& change) {
  if (!refusal.empty()) return refuse_write(what, refusal);
  try {
    change();
  } catch (const Error& e) {
    return refuse_write(what, e.what());
  }
  log(what + " (accepted)");
  return ok_reply();
}

ApiReply Api::post(const std::string& path, const nlohmann::json& body) {
  // A change refused for its form is logged as one refused for its place: every page
  // sees every change asked for, once.
  auto logged = [&](const std::string& what, ApiReply (Api::*change)(const nlohmann::json&)) {
    try {
      return (this->*change)(body);
    } catch (const Error& e) {
      log(what + " (refused: " + e.what() + ")");
      return ApiReply{400, "application/json", error_body(e.what())};
    }
  };
  if (path == "/api/write") return logged(change_name("write", body, "address"), &Api::write);
  if (path == "/api/force") return logged(change_name("force", body, "address"), &Api::force);
  if (path == "/api/mode") return logged(change_name("mode", body, "mode"), &Api::mode);
  if (path == "/api/replay") return replay_post(body);
  if (path.rfind("/api/edit/", 0) == 0) return edit_post(path, body);
  return {404, "application/json", error_body("POST " + path + ": no such API endpoint")};
}

ApiReply Api::write(const nlohmann::json& body) {
  const std::string name = text_field(body, "address", "write");
  const auto& vs = field(body, "values", "write");
  if (!vs.is_array() || vs.empty() || vs.size() > kMaxWriteValues)
    throw Error("write: \"values\" must be an array of 1.." + std::to_string(kMaxWriteValues) + " integers");
  const Address a = resolve(name, *source_.program());
  check_span(a, uint32_t(vs.size()));
  std::vector<uint32_t> values;
  std::string shown;
  for (size_t i = 0; i < vs.size(); ++i) {
    if (!vs[i].is_number_integer()) throw Error("write: values[" + std::to_string(i) + "] is not an integer");
    values.push_back(encode_element(offset_address(a, uint32_t(i)), vs[i].get<int64_t>()));
    shown += (i ? "," : "") + std::to_string(vs[i].get<int64_t>());
  }
  return apply("write " + name + " = " + shown, cannot_write(a, uint32_t(values.size())),
               [&] { source_.write(a, values); });
}

ApiReply Api::force(const nlohmann::json& body) {
  const std::string name = text_field(body, "address", "force");
  const std::string action = text_field(body, "action", "force");
  if (action != "on" && action != "off" && action != "release")
    throw Error("force: \"action\" must be on, off or release, not '" + action + "'");
  const Address a = resolve(name, *source_.program());
  if (a.width != Width::Bit || !is_discrete(a.area)) throw Error("force: " + name + " is not a single discrete");
  return apply("force " + name + " " + action, cannot_force(a), [&] {
    if (action == "release") {
      source_.force(a, ForceAction::Enable);
    } else {
      source_.force(a, ForceAction::Disable);
      source_.force(a, action == "on" ? ForceAction::Set : ForceAction::Reset);
    }
  });
}

ApiReply Api::mode(const nlohmann::json& body) {
  const std::string m = text_field(body, "mode", "mode");
  if (m != "run" && m != "stop") throw Error("mode: \"mode\" must be run or stop, not '" + m + "'");
  return apply("mode " + m, cannot_switch_mode(),
               [&] { source_.set_mode(m == "run" ? RunMode::Run : RunMode::Stop); });
}

ApiReply Api::replay_post(const nlohmann::json& body) {
  Replay* r = source_.replay();
  if (!r) return {404, "application/json", error_body("/api/replay: this source is not a recording")};
  if (body.contains("seek_us")) {
    if (!body["seek_us"].is_number_unsigned()) throw Error("replay: \"seek_us\" must be a non-negative integer");
    r->seek(body["seek_us"].get<uint64_t>());
  } else if (body.contains("step")) {
    const std::string step = text_field(body, "step", "replay");
    const auto& n = field(body, "n", "replay");
    if (!n.is_number_integer()) throw Error("replay: \"n\" must be an integer");
    if (step == "scan") r->step_scans(n.get<int64_t>());
    else if (step == "event") r->step_events(n.get<int64_t>(), watched_addresses(body, *source_.program()));
    else throw Error("replay: \"step\" must be scan or event, not '" + step + "'");
  } else {
    throw Error("replay: expected {\"seek_us\": N} or {\"step\": \"scan|event\", \"n\": K}");
  }
  if (events_.moved) events_.moved();
  return replay_get();
}

// The Edit tab (edit_desk.h). A check changes nothing and needs no more than a read; a
// test, apply or undo is a job, refused here (and logged) when it may not start.
ApiReply Api::edit_post(const std::string& path, const nlohmann::json& body) {
  const std::string what = path.substr(std::string("/api/edit/").size());
  if (what == "check") {
    try {
      return {200, "application/json", dump(edit_->check(text_field(body, "text", "edit check")))};
    } catch (const Error& e) {
      return {400, "application/json", error_body(e.what())};
    }
  }
  try {
    const nlohmann::json job = edit_->start(what, body);
    log("program " + what + " (started)");
    return {202, "application/json", dump(job)};
  } catch (const Error& e) {
    log("program " + what + " (refused: " + e.what() + ")");
    return {409, "application/json", error_body(e.what())};
  }
}

}  // namespace monitor
}  // namespace plc_cell
