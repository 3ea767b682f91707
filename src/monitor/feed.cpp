#include "feed.h"

#include "json_views.h"
#include "plc_cell/core/error.h"

namespace plc_cell {
namespace monitor {

Address resolve(const std::string& text, const ProgramView& program) {
  for (const auto& [name, a] : program.signals)
    if (name == text) return a;
  Address a;
  std::string why;
  if (!try_parse_address(text, &a, &why))
    throw Error("'" + text + "' is neither a signal of the cell nor an address (" + why + ")");
  return a;
}

std::string own_name(const std::string& text, const SourceSet* set, size_t self) {
  if (!set || set->alone()) return text;
  const std::string prefix = set->name(self) + ".";
  return text.rfind(prefix, 0) == 0 ? text.substr(prefix.size()) : text;
}

Subscription parse_subscription(const nlohmann::json& m, const LadderView& ladder, const SourceSet* set, size_t self) {
  if (!m.is_object() || !m.contains("subscribe") || !m["subscribe"].is_object())
    throw Error("expected {\"subscribe\": {...}}");
  const auto& s = m["subscribe"];
  for (const auto& item : s.items())
    if (item.key() != "networks" && item.key() != "watch" && item.key() != "rate_hz")
      throw Error("subscribe." + item.key() + ": unknown field (networks, watch, rate_hz)");
  Subscription out;
  if (s.contains("networks")) {
    if (!s["networks"].is_array()) throw Error("subscribe.networks: expected an array of network indexes");
    for (const auto& n : s["networks"]) {
      if (!n.is_number_unsigned() || n.get<uint64_t>() >= ladder.networks())
        throw Error("subscribe.networks: " + dump(n) + " is not a network (0.." + std::to_string(ladder.networks()) +
                    " exclusive)");
      out.networks.push_back(n.get<size_t>());
    }
    if (out.networks.size() > ladder.networks()) throw Error("subscribe.networks: more entries than networks");
  }
  if (s.contains("watch")) {
    if (!s["watch"].is_array()) throw Error("subscribe.watch: expected an array of names or addresses");
    if (s["watch"].size() > kMaxWatch)
      throw Error("subscribe.watch: " + std::to_string(s["watch"].size()) + " entries, the limit is " +
                  std::to_string(kMaxWatch));
    for (const auto& w : s["watch"]) {
      if (!w.is_string()) throw Error("subscribe.watch: " + dump(w) + " is not a string");
      const std::string name = w.get<std::string>();
      Located at;
      if (set && !set->alone() && set->locate(name, &at) && at.cell != self) {
        out.elsewhere.emplace_back(name, at);
        continue;
      }
      out.watch.push_back(name);
      out.watched.push_back(resolve(own_name(name, set, self), ladder.program()));
    }
  }
  if (s.contains("rate_hz")) {
    if (!s["rate_hz"].is_number_integer() || s["rate_hz"].get<int64_t>() < 1 || s["rate_hz"].get<int64_t>() > 50)
      throw Error("subscribe.rate_hz: " + dump(s["rate_hz"]) + " is not an integer in 1..50");
    out.rate_hz = s["rate_hz"].get<int>();
  }
  out.set = set;
  return out;
}

uint64_t Feed::key(const Address& a) {
  return uint64_t(a.area) << 40 | uint64_t(a.width) << 32 | a.index;
}

Feed::Feed(Subscription s, std::shared_ptr<const LadderView> ladder, const Feed* before)
    : sub_(std::move(s)), ladder_(std::move(ladder)) {
  auto add = [this](const Address& a) {
    if (slot_.emplace(key(a), reads_.size()).second) reads_.push_back(a);
  };
  for (const auto& a : sub_.watched) add(a);
  for (size_t n : sub_.networks)
    for (const auto& a : ladder_->addresses(n)) add(a);
  if (before && before->have_known_) {
    known_ = before->known_;
    known_at_ = before->known_at_;
    known_scan_ = before->known_scan_;
    known_t_us_ = before->known_t_us_;
    have_known_ = true;
  }
}

// The frame's values and forced points: the networks' addresses by address (what the
// drawing shows), the watch list by the names the page gave.
void Feed::add_values(nlohmann::json& j, const std::vector<uint32_t>& values, const std::vector<uint8_t>& forced) const {
  j["values"] = nlohmann::json::object();
  j["forced"] = nlohmann::json::array();
  auto put = [&](const std::string& name, size_t i) {
    if (i >= values.size()) return;
    const bool first = !j["values"].contains(name);
    j["values"][name] = values[i];
    if (first && i < forced.size() && forced[i]) j["forced"].push_back(name);
  };
  for (size_t i = 0; i < reads_.size(); ++i) put(format_address(reads_[i]), i);
  for (size_t i = 0; i < sub_.watch.size(); ++i) put(sub_.watch[i], slot_.at(key(sub_.watched[i])));
}

// The other cells' names: each read from its cell now; one that cannot be read is left out
// and "elsewhere_errors" says why (never a value that was not read).
void Feed::add_elsewhere(nlohmann::json& j) const {
  for (const auto& [name, at] : sub_.elsewhere) {
    try {
      j["values"][name] = sub_.set->source(at.cell).read({at.address}).values.at(0);
    } catch (const std::exception& e) {
      j["elsewhere_errors"][name] = e.what();
    }
  }
}

nlohmann::json Feed::frame(Source& source) {
  Frame f;
  try {
    f = source.read(reads_);
  } catch (const std::exception& e) {
    failure_ = e.what();
    prev_.clear();  // the next good frame has no edges to judge from
    return stale_frame(failure_);
  }
  failure_.clear();
  if (prev_.size() != f.values.size()) prev_ = f.values;  // the first frame: no edges yet
  nlohmann::json j = {{"type", "frame"}, {"scan", f.scan}, {"t_us", f.t_us},
                      {"mode", mode_text(f.mode, f.mode_known)}};
  add_values(j, f.values, f.forced);
  add_elsewhere(j);
  auto lookup = [this](const std::vector<uint32_t>& v) {
    return [this, &v](const Address& a) {
      auto it = slot_.find(key(a));
      return it == slot_.end() ? 0u : v[it->second];
    };
  };
  const bool scanned = f.mode_known && f.mode == RunMode::Run;
  j["flow"] = nlohmann::json::array();
  for (size_t n : sub_.networks)
    j["flow"].push_back({{"net", n},
                         {"on", scanned ? nlohmann::json(ladder_->flow(n, lookup(f.values), lookup(prev_)))
                                        : nlohmann::json::array()}});
  if (!f.mode_known) j["no_flow"] = "RUN or STOP is not known (the PLC does not report it): no power flow is drawn";
  else if (!scanned) j["no_flow"] = "STOP: no network runs, so none carries power";
  j["stale"] = nullptr;
  for (size_t i = 0; i < reads_.size(); ++i)
    known_[key(reads_[i])] = Known{f.values[i], i < f.forced.size() && f.forced[i]};
  known_at_ = std::chrono::steady_clock::now();
  known_scan_ = f.scan;
  known_t_us_ = f.t_us;
  have_known_ = true;
  prev_ = std::move(f.values);
  return j;
}

// The last values read of what the page shows (those never read are left out), no flow.
nlohmann::json Feed::stale_frame(const std::string& why) {
  std::vector<uint32_t> values;
  std::vector<uint8_t> forced;
  std::vector<size_t> missing;
  for (size_t i = 0; i < reads_.size(); ++i) {
    auto it = known_.find(key(reads_[i]));
    if (it == known_.end()) missing.push_back(i);
    values.push_back(it == known_.end() ? 0 : it->second.value);
    forced.push_back(it != known_.end() && it->second.forced);
  }
  nlohmann::json j = {{"type", "frame"}, {"scan", known_scan_}, {"t_us", known_t_us_}, {"mode", "unknown"}};
  add_values(j, values, forced);
  add_elsewhere(j);
  for (size_t i : missing) j["values"].erase(format_address(reads_[i]));
  for (size_t i = 0; i < sub_.watch.size(); ++i)
    if (!known_.count(key(sub_.watched[i]))) j["values"].erase(sub_.watch[i]);
  j["flow"] = nlohmann::json::array();
  for (size_t n : sub_.networks) j["flow"].push_back({{"net", n}, {"on", nlohmann::json::array()}});
  j["no_flow"] = "the values are not current: no power flow is drawn from them";
  nlohmann::json age = nullptr;
  if (have_known_)
    age = uint64_t(std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - known_at_)
                       .count());
  j["stale"] = {{"age_ms", age}, {"error", why}};
  return j;
}

}  // namespace monitor
}  // namespace plc_cell
