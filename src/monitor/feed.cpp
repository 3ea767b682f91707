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

Subscription parse_subscription(const nlohmann::json& m, const LadderView& ladder) {
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
      out.watch.push_back(w.get<std::string>());
      out.watched.push_back(resolve(out.watch.back(), ladder.program()));
    }
  }
  if (s.contains("rate_hz")) {
    if (!s["rate_hz"].is_number_integer() || s["rate_hz"].get<int64_t>() < 1 || s["rate_hz"].get<int64_t>() > 50)
      throw Error("subscribe.rate_hz: " + dump(s["rate_hz"]) + " is not an integer in 1..50");
    out.rate_hz = s["rate_hz"].get<int>();
  }
  return out;
}

uint64_t Feed::key(const Address& a) {
  return uint64_t(a.area) << 40 | uint64_t(a.width) << 32 | a.index;
}

Feed::Feed(Subscription s, std::shared_ptr<const LadderView> ladder) : sub_(std::move(s)), ladder_(std::move(ladder)) {
  auto add = [this](const Address& a) {
    if (slot_.emplace(key(a), reads_.size()).second) reads_.push_back(a);
  };
  for (const auto& a : sub_.watched) add(a);
  for (size_t n : sub_.networks)
    for (const auto& a : ladder_->addresses(n)) add(a);
}

nlohmann::json Feed::frame(Source& source) {
  Frame f = source.read(reads_);
  if (prev_.size() != f.values.size()) prev_ = f.values;  // the first frame: no edges yet
  nlohmann::json j = {{"type", "frame"}, {"scan", f.scan}, {"t_us", f.t_us}, {"mode", mode_text(f.mode)}};
  j["values"] = nlohmann::json::object();
  // The networks' addresses by address (what the drawing shows), the watch list as written.
  for (size_t i = 0; i < reads_.size(); ++i) j["values"][format_address(reads_[i])] = f.values[i];
  for (size_t i = 0; i < sub_.watch.size(); ++i) j["values"][sub_.watch[i]] = f.values[slot_.at(key(sub_.watched[i]))];
  auto lookup = [this](const std::vector<uint32_t>& v) {
    return [this, &v](const Address& a) {
      auto it = slot_.find(key(a));
      return it == slot_.end() ? 0u : v[it->second];
    };
  };
  j["flow"] = nlohmann::json::array();
  for (size_t n : sub_.networks)
    j["flow"].push_back({{"net", n}, {"on", ladder_->flow(n, lookup(f.values), lookup(prev_))}});
  prev_ = std::move(f.values);
  return j;
}

}  // namespace monitor
}  // namespace plc_cell
