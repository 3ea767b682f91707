#include "edit_desk.h"

#include <algorithm>
#include <vector>

#include "ladder_view.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/il_parser.h"

namespace plc_cell {
namespace monitor {

namespace {

// A network's IL as its logic: comments and spacing dropped.
std::string identity(const nlohmann::json& network) {
  std::string out;
  for (const auto& l : network.value("il", nlohmann::json::array())) {
    std::string t = l.value("text", "");
    if (const auto semi = t.find(';'); semi != std::string::npos) t.erase(semi);
    std::string word;
    bool space = false;
    for (char c : t) {
      if (c == ' ' || c == '\t' || c == '\r') {
        space = !word.empty();
        continue;
      }
      if (space) word += ' ';
      space = false;
      word += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
    if (!word.empty()) out += word + "\n";
  }
  return out;
}

std::string outcome_line(const ChangeOutcome& o) {
  std::string s = "program " + std::string(o.undo ? "undo " : "change ") + o.result;
  if (!o.why.empty()) s += ": " + o.why;
  if (o.gate.configured) s += " (gate: " + o.gate.summary + ")";
  return s;
}

}  // namespace

nlohmann::json changed_networks(const nlohmann::json& old_layout, const nlohmann::json& new_layout) {
  const auto& a = old_layout.at("networks");
  const auto& b = new_layout.at("networks");
  const size_t n = a.size(), m = b.size();
  std::vector<std::string> ia, ib;
  for (const auto& x : a) ia.push_back(identity(x));
  for (const auto& x : b) ib.push_back(identity(x));
  // Longest common subsequence of the networks; what is left over changed.
  std::vector<uint32_t> len((n + 1) * (m + 1), 0);
  auto at = [&](size_t i, size_t j) -> uint32_t& { return len[i * (m + 1) + j]; };
  for (size_t i = n; i-- > 0;)
    for (size_t j = m; j-- > 0;) at(i, j) = ia[i] == ib[j] ? at(i + 1, j + 1) + 1 : std::max(at(i + 1, j), at(i, j + 1));
  nlohmann::json out = nlohmann::json::array();
  std::vector<nlohmann::json> gone, come;
  auto flush = [&] {
    for (size_t k = 0; k < std::max(gone.size(), come.size()); ++k)
      out.push_back({{"old", k < gone.size() ? gone[k] : nlohmann::json(nullptr)},
                     {"new", k < come.size() ? come[k] : nlohmann::json(nullptr)}});
    gone.clear();
    come.clear();
  };
  size_t i = 0, j = 0;
  while (i < n || j < m) {
    if (i < n && j < m && ia[i] == ib[j]) {
      flush();
      ++i, ++j;
    } else if (j < m && (i == n || at(i, j + 1) >= at(i + 1, j))) {
      come.push_back(b[j++]);
    } else {
      gone.push_back(a[i++]);
    }
  }
  flush();
  return out;
}

EditDesk::EditDesk(Source& source, std::string apply_refusal, std::function<void(const std::string&)> log)
    : source_(source), apply_refusal_(std::move(apply_refusal)), log_(std::move(log)) {}

EditDesk::~EditDesk() {
  if (worker_.joinable()) worker_.join();
}

ProgramChanges& EditDesk::changes() const {
  ProgramChanges* c = source_.changes();
  if (!c) throw Error("this source's program cannot be changed from the monitor (only a live cell's can)");
  return *c;
}

nlohmann::json EditDesk::state() const {
  ProgramChanges* c = source_.changes();
  if (!c) return {{"available", false}, {"why", "only a live cell's program can be changed from the monitor"}};
  return {{"available", true},          {"apply", apply_refusal_.empty()}, {"apply_refusal", apply_refusal_},
          {"file", c->file()},          {"text", c->text()},               {"hash", c->hash()},
          {"gate", c->has_gate()},      {"job", job()}};
}

nlohmann::json EditDesk::check(const std::string& text) const {
  ProgramChanges& c = changes();
  const ChangeOutcome o = c.check(text);
  nlohmann::json j = to_json(o);
  if (!o.errors.empty()) return j;
  const auto old_view = source_.program();
  auto view = std::make_shared<ProgramView>();
  view->file = old_view->file;
  view->text = text;
  view->signals = old_view->signals;
  const FunctionTable* functions = source_.functions();
  static const FunctionTable core = FunctionTable::with_core_functions();
  view->program = parse_program(text, old_view->file, functions ? *functions : core);
  const nlohmann::json now = LadderView(old_view, functions).json();
  const nlohmann::json next = LadderView(view, functions).json();
  j["networks"] = changed_networks(now, next);
  j["signals"] = next.value("signals", nlohmann::json::object());
  return j;
}

nlohmann::json EditDesk::job() const {
  std::lock_guard<std::mutex> lk(mu_);
  if (!job_id_) return {{"id", 0}, {"state", "none"}};
  return {{"id", job_id_}, {"what", job_what_}, {"state", running_ ? "running" : "done"}, {"result", job_result_}};
}

nlohmann::json EditDesk::log(size_t last) const { return changes().log(last); }

void EditDesk::run(const std::string& what, std::function<nlohmann::json()> work) {
  std::lock_guard<std::mutex> lk(mu_);
  if (running_) throw Error("edit: a " + job_what_ + " is running; wait for it (GET /api/edit/job)");
  if (worker_.joinable()) worker_.join();  // done: its thread is ending
  ++job_id_;
  running_ = true;
  job_what_ = what;
  job_result_ = nullptr;
  worker_ = std::thread([this, work = std::move(work)] {
    nlohmann::json result;
    try {
      result = work();
    } catch (const std::exception& e) {
      result = {{"result", "refused"}, {"why", e.what()}};
    }
    std::lock_guard<std::mutex> lk(mu_);
    job_result_ = std::move(result);
    running_ = false;
  });
}

nlohmann::json EditDesk::start(const std::string& what, const nlohmann::json& body) {
  ProgramChanges& c = changes();
  auto text = [&] {
    const auto it = body.find("text");
    if (it == body.end() || !it->is_string()) throw Error("edit " + what + ": \"text\" must be the program's IL");
    return it->get<std::string>();
  };
  if (what == "test") {
    run(what, [&c, t = text()] { return to_json(c.test(t)); });
  } else if (what == "apply" || what == "undo") {
    if (!apply_refusal_.empty()) throw Error("edit " + what + ": " + apply_refusal_);
    ChangeRequest r;
    r.source = ChangeSource::Page;
    if (what == "apply") {
      r.text = text();
      r.force = body.value("force", false);
      r.reason = body.value("reason", "");
      if (r.force && r.reason.empty()) throw Error("edit apply: apply anyway needs a \"reason\"");
    }
    run(what, [this, &c, r, what] {
      const ChangeOutcome o = what == "undo" ? c.undo(ChangeSource::Page) : c.apply(r);
      if (log_) log_(outcome_line(o));
      return to_json(o);
    });
  } else {
    throw Error("edit: no such action '" + what + "' (test, apply, undo)");
  }
  return job();
}

}  // namespace monitor
}  // namespace plc_cell
