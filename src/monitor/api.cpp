#include "api.h"

#include <cstdio>

#include "feed.h"
#include "json_views.h"
#include "plc_cell/core/error.h"
#include "static_files.h"

namespace plc_cell {
namespace monitor {
namespace {

ApiReply json_reply(const nlohmann::json& j, int status = 200) { return {status, "application/json", dump(j)}; }
ApiReply error_reply(int status, const std::string& why) { return {status, "application/json", error_body(why)}; }

int hex(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// %XX and '+' decoded; throws on a broken escape.
std::string url_decode(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') out += ' ';
    else if (s[i] != '%') out += s[i];
    else {
      if (i + 2 >= s.size() || hex(s[i + 1]) < 0 || hex(s[i + 2]) < 0) throw Error("a broken %-escape in the query");
      out += char(hex(s[i + 1]) * 16 + hex(s[i + 2]));
      i += 2;
    }
  }
  return out;
}

// The value of key in a query string ("a=D0,X1&b=2"); false when absent.
bool query_value(const std::string& query, const std::string& key, std::string* out) {
  size_t start = 0;
  while (start <= query.size()) {
    size_t end = query.find('&', start);
    if (end == std::string::npos) end = query.size();
    const std::string part = query.substr(start, end - start);
    if (part.rfind(key + "=", 0) == 0) {
      *out = url_decode(part.substr(key.size() + 1));
      return true;
    }
    start = end + 1;
  }
  return false;
}

std::vector<std::string> split_names(const std::string& s) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= s.size()) {
    size_t end = s.find(',', start);
    if (end == std::string::npos) end = s.size();
    if (end > start) out.push_back(s.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

std::string signal_name(const Address& a, const ProgramView& program) {
  for (const auto& [name, at] : program.signals)
    if (at == a) return name;
  return "";
}

}  // namespace

Api::Api(Source& source, const HttpSettings& settings, const std::string& bound_host, std::string token, Events events)
    : source_(source), settings_(settings), guard_(bound_host, settings.allowed_hosts), token_(std::move(token)),
      events_(std::move(events)) {
  std::string why;
  if (!settings.edit) why = "this monitor does not change the program (servers.http.edit: false)";
  edit_ = std::make_unique<EditDesk>(source_, why, [this](const std::string& text) { log(text); });
}

std::shared_ptr<const LadderView> Api::ladder() {
  auto program = source_.program();
  std::lock_guard<std::mutex> lk(ladder_mu_);
  if (!ladder_ || &ladder_->program() != program.get()) ladder_ = std::make_shared<LadderView>(program, source_.functions());
  return ladder_;
}

nlohmann::json Api::status_json_now() {
  CellStatus s = source_.status();
  // The page may switch RUN/STOP only where this server lets it (api_control.cpp).
  std::string refusal = cannot(Change::Mode);
  if (refusal.empty() && !s.mode_switchable) refusal = "this source cannot switch RUN/STOP";
  if (refusal.empty()) refusal = cannot_switch_mode();
  s.mode_switchable = refusal.empty();
  nlohmann::json j = status_json(s);
  j["mode_refusal"] = refusal;
  // Each forced point with its name and the state it is held in.
  std::vector<uint32_t> state;
  try {
    if (!s.forced.empty()) state = source_.read(s.forced).values;
  } catch (const std::exception&) {
    // A source that cannot be read now: the states are not known (null).
  }
  const auto program = source_.program();
  j["forced"] = nlohmann::json::array();
  for (size_t i = 0; i < s.forced.size(); ++i)
    j["forced"].push_back({{"address", format_address(s.forced[i])},
                           {"name", signal_name(s.forced[i], *program)},
                           {"state", i < state.size() ? nlohmann::json(state[i]) : nlohmann::json(nullptr)}});
  return j;
}

nlohmann::json Api::status_message() {
  // Every page gets the status each second: one gathering serves all of them.
  std::lock_guard<std::mutex> lk(status_mu_);
  const auto now = std::chrono::steady_clock::now();
  if (status_.is_null() || now - status_at_ >= std::chrono::milliseconds(500)) {
    status_ = status_json_now();
    status_["type"] = "status";
    status_at_ = now;
  }
  return status_;
}

void Api::log(const std::string& text) {
  nlohmann::json t_us = nullptr;  // null: the source's clock cannot be read now
  try {
    t_us = source_.now_us();
  } catch (const std::exception&) {
  }
  if (events_.log) events_.log(dump({{"type", "log"}, {"t_us", t_us}, {"text", text}}));
}

void Api::note_read(const std::string& failure) {
  std::string text;
  {
    std::lock_guard<std::mutex> lk(read_mu_);
    const auto now = std::chrono::steady_clock::now();
    if (!failure.empty() && read_state_ != ReadState::Down) {
      read_state_ = ReadState::Down;
      down_since_ = now;
      text = failure;
    } else if (failure.empty() && read_state_ == ReadState::Down) {
      read_state_ = ReadState::Up;
      char down[32];
      std::snprintf(down, sizeof down, "%.1f", std::chrono::duration<double>(now - down_since_).count());
      text = source_.describe() + ": values read again, after " + down + " s without";
    } else if (failure.empty()) {
      read_state_ = ReadState::Up;
    }
  }
  if (!text.empty()) log(text);
}

ApiReply Api::handle(const ApiRequest& r) {
  try {
    if (const std::string why = refusal(r); !why.empty()) return error_reply(403, why);
    const auto q = r.target.find('?');
    const std::string path = r.target.substr(0, q);
    const std::string query = q == std::string::npos ? "" : r.target.substr(q + 1);
    if (r.method == "GET") return get(path, query);
    if (r.method != "POST") return error_reply(405, r.method + " " + path + ": only GET and POST are served");
    if (path.rfind("/api/", 0) != 0) return error_reply(405, "POST " + path + ": only the API takes POST");
    if (r.token != token_)
      return refuse_write("POST " + path,
                          r.token.empty() ? "no X-Plc-Token header (GET /api/session gives it)" : "wrong X-Plc-Token");
    if (r.body.size() > max_body(path))
      return error_reply(413, "request body over the limit of " + std::to_string(max_body(path)) + " bytes");
    const auto body = nlohmann::json::parse(r.body, nullptr, false);
    if (body.is_discarded() || !body.is_object())
      return error_reply(400, "POST " + path + ": the body is not a JSON object");
    return post(path, body);
  } catch (const Error& e) {
    return error_reply(400, e.what());
  } catch (const std::exception& e) {
    return error_reply(400, std::string("bad request: ") + e.what());
  }
}

ApiReply Api::get(const std::string& path, const std::string& query) {
  if (path == "/api/session")
    return json_reply({{"token", token_},
                       {"writable", settings_.writable.describe()},
                       {"source", source_.describe()},
                       {"kind", kind_text(source_.kind())},
                       {"rate_hz", kDefaultRateHz}});
  if (path == "/api/ladder") return json_reply(ladder()->json());
  if (path == "/api/status") return json_reply(status_json_now());
  if (path == "/api/read") return read(query);
  if (path == "/api/access") return access(query);
  if (path == "/api/coverage") {
    auto seen = source_.coverage();
    if (!seen) return json_reply({{"available", false}, {"seen", nlohmann::json::array()}});
    return json_reply({{"available", true}, {"seen", *seen}});
  }
  if (path == "/api/replay") return replay_get();
  if (path == "/api/edit" || path.rfind("/api/edit/", 0) == 0) return edit_get(path, query);
  if (path == "/api/replay/history") return replay_history(query);
  if (path.rfind("/api/", 0) == 0) return error_reply(404, path + ": no such API endpoint");
  const auto file = static_file(path, settings_.asset_root.empty() ? default_asset_root() : settings_.asset_root,
                                settings_.vendor_root);
  return {file.status, file.type, file.body};
}

bool Api::foreign(const std::string& name, Located* at) const {
  return set_ && !set_->alone() && set_->locate(name, at) && at->cell != self_;
}

// Another cell's name is read from that cell, at its own instant (cells scan apart).
ApiReply Api::read(const std::string& query) {
  std::vector<std::string> names;
  std::string list;
  if (!query_value(query, "a", &list)) throw Error("/api/read: no a= (a=D0,X1,start_pb)");
  const auto program = source_.program();
  std::vector<Address> addrs;
  std::vector<std::pair<size_t, Located>> others;  // index in names, where
  for (const auto& n : split_names(list)) {
    Located at;
    if (foreign(n, &at)) others.emplace_back(names.size(), at);
    else addrs.push_back(resolve(own_name(n, set_, self_), *program));
    names.push_back(n);
  }
  if (names.empty()) throw Error("/api/read: a= names nothing");
  if (names.size() > kMaxWatch)
    throw Error("/api/read: " + std::to_string(names.size()) + " names, the limit is " + std::to_string(kMaxWatch));
  const Frame f = source_.read(addrs);
  nlohmann::json values = nlohmann::json::object();
  size_t own = 0, other = 0;
  for (size_t i = 0; i < names.size(); ++i) {
    if (other < others.size() && others[other].first == i) {
      const Located& at = others[other++].second;
      values[names[i]] = set_->source(at.cell).read({at.address}).values.at(0);
    } else {
      values[names[i]] = f.values.at(own++);
    }
  }
  return json_reply({{"scan", f.scan}, {"t_us", f.t_us}, {"mode", mode_text(f.mode, f.mode_known)}, {"values", values}});
}

ApiReply Api::access(const std::string& query) {
  std::string list;
  if (!query_value(query, "a", &list)) throw Error("/api/access: no a= (a=D0,X1,start_pb)");
  const auto names = split_names(list);
  if (names.empty() || names.size() > kMaxWatch)
    throw Error("/api/access: a= names 1 to " + std::to_string(kMaxWatch) + " names");
  const auto program = source_.program();
  nlohmann::json out = nlohmann::json::object();
  for (const auto& n : names) {
    Located at;
    if (foreign(n, &at)) {
      // A page changes its own cell only: every write is checked and logged where it lands.
      const std::string why = n + " is cell " + set_->name(at.cell) + "'s: change it on that cell's page";
      out[n] = {{"write", why}, {"force", why}};
      continue;
    }
    const Address a = resolve(own_name(n, set_, self_), *program);
    out[n] = {{"write", cannot_write(a, 1)}, {"force", cannot_force(a)}};
  }
  return json_reply(out);
}

ApiReply Api::replay_get() {
  Replay* r = source_.replay();
  if (!r) return error_reply(404, "/api/replay: this source is not a recording");
  nlohmann::json failure = nullptr, text = nullptr;
  if (auto f = r->failure_us()) {
    failure = *f;
    text = r->failure_text();
  }
  return json_reply({{"begin_us", r->begin_us()},
                     {"end_us", r->end_us()},
                     {"cursor_us", r->cursor_us()},
                     {"scans", r->scans()},
                     {"failure_us", failure},
                     {"failure", text}});
}

// GET /api/replay/history?a=X3,R0&from_us=0&to_us=4500000: each name's recorded values.
ApiReply Api::replay_history(const std::string& query) {
  Replay* r = source_.replay();
  if (!r) return error_reply(404, "/api/replay/history: this source is not a recording");
  std::string list, from, to;
  if (!query_value(query, "a", &list)) return error_reply(400, "/api/replay/history: no a= (a=D0,X1,start_pb)");
  const auto names = split_names(list);
  if (names.empty() || names.size() > kMaxWatch)
    return error_reply(400, "/api/replay/history: a= names 1 to " + std::to_string(kMaxWatch) + " addresses");
  uint64_t from_us = r->begin_us(), to_us = r->end_us();
  try {
    if (query_value(query, "from_us", &from)) from_us = std::stoull(from);
    if (query_value(query, "to_us", &to)) to_us = std::stoull(to);
  } catch (const std::exception&) {
    return error_reply(400, "/api/replay/history: from_us and to_us are whole microseconds");
  }
  const auto program = source_.program();
  std::vector<Address> addrs;
  for (const auto& n : names) addrs.push_back(resolve(n, *program));
  const History h = r->history(addrs, from_us, to_us);
  nlohmann::json series = nlohmann::json::object();
  for (size_t i = 0; i < names.size(); ++i) series[names[i]] = h.series.at(i);
  nlohmann::json cut = nullptr;
  if (h.cut_us) cut = *h.cut_us;
  return json_reply({{"series", series}, {"cut_us", cut}});
}

// GET /api/edit, /api/edit/job, /api/edit/log?last=N (edit_desk.h).
ApiReply Api::edit_get(const std::string& path, const std::string& query) {
  if (path == "/api/edit") return json_reply(edit_->state());
  if (path == "/api/edit/job") return json_reply(edit_->job());
  if (path == "/api/edit/log") {
    std::string last;
    size_t n = 200;
    if (query_value(query, "last", &last)) {
      if (last.empty() || last.size() > 6 || last.find_first_not_of("0123456789") != std::string::npos)
        return error_reply(400, "/api/edit/log: last= is a whole number of entries");
      n = static_cast<size_t>(std::stoul(last));
    }
    try {
      return json_reply(edit_->log(n));
    } catch (const Error& e) {
      return error_reply(404, e.what());
    }
  }
  return error_reply(404, path + ": no such API endpoint");
}

}  // namespace monitor
}  // namespace plc_cell
