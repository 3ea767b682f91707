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

// The elements of the memory a write of count values at a covers: WY8 x1 is Y8..Y23,
// DR0 x1 is R0 and R1.
uint32_t elements(const Address& a, uint32_t count) {
  uint32_t per = 1;
  if (is_discrete(a.area)) per = a.width == Width::Bit ? 1 : a.width == Width::Word ? 16 : 32;
  else if (a.width == Width::DWord && a.area != Area::RC) per = 2;
  return count * per;
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
  if (path == "/api/write") return write(body);
  if (path == "/api/force") return force(body);
  if (path == "/api/mode") return mode(body);
  if (path == "/api/replay") return replay_post(body);
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
  return apply("write " + name + " = " + shown, not_writable(a, elements(a, uint32_t(values.size()))),
               [&] { source_.write(a, values); });
}

ApiReply Api::force(const nlohmann::json& body) {
  const std::string name = text_field(body, "address", "force");
  const std::string action = text_field(body, "action", "force");
  if (action != "on" && action != "off" && action != "release")
    throw Error("force: \"action\" must be on, off or release, not '" + action + "'");
  const Address a = resolve(name, *source_.program());
  if (a.width != Width::Bit) throw Error("force: " + name + " is not a single discrete");
  return apply("force " + name + " " + action, not_writable(a, 1), [&] {
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
  // RUN/STOP reaches every address: only a server writable everywhere switches it.
  const std::string refusal =
      settings_.writable.everything() ? "" : "RUN/STOP needs writable: all (writable: " + settings_.writable.describe() + ")";
  return apply("mode " + m, refusal, [&] { source_.set_mode(m == "run" ? RunMode::Run : RunMode::Stop); });
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

}  // namespace monitor
}  // namespace plc_cell
