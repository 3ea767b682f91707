#include "plc_cell/hsc/hsc_config.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"

namespace plc_cell {
namespace hsc {

const HhscPins& hhsc_pins(int n) {
  static const HhscPins pins[4] = {{{0}, 1, 2, 3}, {{4, 1}, 5, 6, 7}, {{8, 4, 5}, 9, 10, 11}, {{12, 5}, 13, 14, 15}};
  return pins[n];
}
uint32_t mask_relay(int n) {
  static const uint32_t m[8] = {1940, 1946, 1976, 1979, 1982, 1984, 1986, 1988};
  return m[n];
}
int clear_relay(int n) {
  static const int m[8] = {1941, 1947, 1977, 1980, -1, -1, -1, -1};
  return m[n];
}
uint32_t dir_relay(int n) {
  static const uint32_t m[8] = {1942, 1948, 1978, 1981, 1983, 1985, 1987, 1989};
  return m[n];
}

namespace {

class Parse : public YamlReader {
 public:
  using YamlReader::YamlReader;

  // "X5" -> 5; only X0-X15 carry high-speed functions.
  int pin(const YAML::Node& n, const std::string& key) const {
    std::string s = str(n, key);
    for (auto& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (s.size() < 2 || s[0] != 'X' || !std::all_of(s.begin() + 1, s.end(), ::isdigit) || s.size() > 3)
      fail(n, key, "'" + n.as<std::string>() + "' is not an input X0-X15");
    const int x = std::stoi(s.substr(1));
    if (x > 15) fail(n, key, "'" + s + "': only X0-X15 are high-speed inputs");
    return x;
  }

  // "X17" -> 17 for the inputs with capture and filter settings (X0-X35).
  int main_input(const YAML::Node& n, const std::string& key) const {
    std::string s = upper(str(n, key));
    if (s.size() < 2 || s.size() > 3 || s[0] != 'X' || !std::all_of(s.begin() + 1, s.end(), ::isdigit) ||
        std::stoi(s.substr(1)) >= kFilteredInputs)
      fail(n, key, "'" + s + "' is not an input X0-X35 of the main unit");
    return std::stoi(s.substr(1));
  }

  static std::string upper(std::string s) {
    for (auto& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return s;
  }

  // Each of X0-X15 serves one function (manual §10.2).
  void use(int x, const YAML::Node& at, const std::string& key, const std::string& what) {
    auto it = uses_.find(x);
    if (it != uses_.end())
      fail(at, key, "X" + std::to_string(x) + " is already used as " + it->second.first + " (line " +
                        std::to_string(it->second.second) + "); each of X0-X15 can serve only one function");
    uses_[x] = {what, line(at)};
  }

 private:
  std::map<int, std::pair<std::string, int>> uses_;
};

Mode parse_mode(const Parse& p, const YAML::Node& n, const std::string& key) {
  std::string s = p.str(n, key);
  for (auto& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (s.rfind("MD", 0) == 0) s = s.substr(2);
  if (s.size() != 1 || s[0] < '0' || s[0] > '7') p.fail(n, key, "mode must be MD0 ... MD7");
  return static_cast<Mode>(s[0] - '0');
}

// The TRi decodings (docs/counters-and-interrupts.md "TRi encoder decoding") decode
// a quadrature pair and fix the counts per cycle themselves: they go with MD4, the
// A/B mode without a multiplier of its own.
Decoding parse_decoding(const Parse& p, const YAML::Node& n, const std::string& key, Mode mode) {
  const std::string s = p.str(n, key);
  Decoding d;
  if (!decoding_from_name(s, &d)) p.fail(n, key, "'" + s + "': expected simple, enhanced, x1, x2 or x4");
  if (!is_ab(mode))
    p.fail(n, key, "decoding is for an A/B counter (mode: MD4); MD" + std::to_string(int(mode)) +
                       " counts " + (mode <= Mode::UDx2 ? "U/D" : "P/R") + " pulses");
  if (mode != Mode::AB)
    p.fail(n, key, "MD" + std::to_string(int(mode)) + " has its own multiplier; use mode: MD4 with decoding: " + s);
  return d;
}

// The A pin: fixed (with alternatives) on HHSC, free on SHSC.
int parse_pin_a(Parse& p, int n, const YAML::Node& c, const std::string& key, Mode mode, const char* a_name) {
  if (n >= 4) {
    if (!c["a"]) p.fail(c, key, "a software counter needs its " + std::string(a_name) + " input, e.g. a: X4");
    return p.pin(c["a"], key + ".a");
  }
  const HhscPins& hp = hhsc_pins(n);
  if (!c["a"] || c["a"].IsNull() || p.str(c["a"], key + ".a") == "true") return hp.a[0];
  const int x = p.pin(c["a"], key + ".a");
  if (std::find(hp.a.begin(), hp.a.end(), x) == hp.a.end() || (is_ab(mode) && x != hp.a[0]))
    p.fail(c["a"], key + ".a", "HSC" + std::to_string(n) + " cannot take its " + a_name + " input on X" + std::to_string(x));
  return x;
}

void parse_invert(Parse& p, const YAML::Node& inv, const std::string& key, bool hard, CounterDef& d) {
  if (!hard) p.fail(inv, key + ".invert", "polarity inversion is a hardware-counter (HSC0-HSC3) setting");
  if (!inv.IsSequence()) p.fail(inv, key + ".invert", "expected a list of count, mask, clear");
  for (const auto& e : inv) {
    const std::string s = p.str(e, key + ".invert");
    if (s == "count") d.inv_count = true;
    else if (s == "mask") d.inv_mask = true;
    else if (s == "clear") d.inv_clear = true;
    else p.fail(e, key + ".invert", "'" + s + "': expected count, mask or clear");
  }
}

void parse_counter(Parse& p, int n, const YAML::Node& c, CounterDef& d) {
  const std::string key = "counters.hsc" + std::to_string(n);
  const std::string who = "HSC" + std::to_string(n);
  const bool hard = n < 4;
  p.only(c, key, {"type", "mode", "a", "b", "mask", "clear", "invert", "name", "decoding"});
  d.line = Parse::line(c);
  d.name = c["name"] ? p.topic_name(c["name"], key + ".name", "counter") : "hsc" + std::to_string(n);
  if (c["type"]) {
    const std::string t = p.str(c["type"], key + ".type");
    if (t == "timer") {
      if (!hard) p.fail(c["type"], key + ".type", "only HSC0-HSC3 can be high-speed timers (HST0-HST3)");
      d.used = d.timer = true;
      if (!c["name"]) d.name = "hst" + std::to_string(n);
      for (const char* k : {"mode", "a", "b", "mask", "clear", "invert", "decoding"})
        if (c[k]) p.fail(c[k], key + "." + k, "a high-speed timer takes no further items");
      return;
    }
    if (t != "counter") p.fail(c["type"], key + ".type", "expected counter or timer");
  }
  if (!c["mode"]) p.fail(c, key, "needs mode: MD0 ... MD7 (leave the counter out if it is not used)");
  d.used = true;
  d.mode = parse_mode(p, c["mode"], key + ".mode");
  if (!hard && d.mode != Mode::UD && d.mode != Mode::PR && d.mode != Mode::AB)
    p.fail(c["mode"], key + ".mode", "software counters (HSC4-HSC7) count in MD0, MD2 or MD4 only");
  if (c["decoding"]) d.decoding = parse_decoding(p, c["decoding"], key + ".decoding", d.mode);
  const char* a_name = is_ab(d.mode) ? "A" : (d.mode <= Mode::UDx2 ? "U" : "P");
  const char* b_name = is_ab(d.mode) ? "B" : (d.mode <= Mode::UDx2 ? "D" : "R");
  d.pin_a = parse_pin_a(p, n, c, key, d.mode, a_name);
  // B pin: required in A/B modes, optional otherwise (absent R: the direction relay).
  auto optional_pin = [&](const char* k, int fixed) {
    const YAML::Node v = c[k];
    if (!v || v.IsNull()) return kNoPin;
    const std::string s = p.str(v, key + "." + k);
    if (s == "false") return kNoPin;
    if (s == "true") {
      if (fixed < 0) p.fail(v, key + "." + k, "a software counter needs a pin here, e.g. X5");
      return fixed;
    }
    const int x = p.pin(v, key + "." + k);
    if (fixed >= 0 && x != fixed)
      p.fail(v, key + "." + k, who + "'s " + k + " input is X" + std::to_string(fixed) + " (fixed pin)");
    return x;
  };
  d.pin_b = optional_pin("b", hard ? hhsc_pins(n).b : -1);
  if (is_ab(d.mode)) {
    if (hard) d.pin_b = hhsc_pins(n).b;
    if (d.pin_b == kNoPin) p.fail(c, key, "A/B mode needs its B input, e.g. b: X" + std::to_string(d.pin_a + 1));
    if (d.pin_a % 2 != 0 || d.pin_b != d.pin_a + 1)
      p.fail(c["b"] ? c["b"] : c, key + ".b", "A and B must be a pair: A even, B the next input (e.g. X8, X9)");
  }
  d.pin_mask = optional_pin("mask", hard ? hhsc_pins(n).mask : -1);
  d.pin_clear = optional_pin("clear", hard ? hhsc_pins(n).clear : -1);
  if (c["invert"]) parse_invert(p, c["invert"], key, hard, d);
  auto at = [&](const char* k) { return c[k] ? c[k] : c; };
  p.use(d.pin_a, at("a"), key + ".a", "the " + std::string(a_name) + " input of " + who);
  if (d.pin_b != kNoPin) p.use(d.pin_b, at("b"), key + ".b", "the " + std::string(b_name) + " input of " + who);
  if (d.pin_mask != kNoPin) p.use(d.pin_mask, at("mask"), key + ".mask", "the MASK input of " + who);
  if (d.pin_clear != kNoPin) p.use(d.pin_clear, at("clear"), key + ".clear", "the CLEAR input of " + who);
}

// One group's setting: a cut-off frequency by name (X0-X15) or a time, 1-15 ms
// (every group) or 0.1-1.5 ms in 0.1 ms steps (X0-X15).
uint64_t parse_filter(const Parse& p, const YAML::Node& v, const std::string& key, const FilterGroup& g) {
  const std::string s = p.str(v, key);
  std::string names;
  for (const auto& f : filter_frequencies()) {
    if (Parse::upper(s) == Parse::upper(f.name)) {
      if (!g.frequency) p.fail(v, key, std::string(g.name) + " has a time-domain filter only (1ms ... 15ms)");
      return frequency_filter_ns(f.hz);
    }
    names += std::string(names.empty() ? "" : ", ") + f.name;
  }
  if (Parse::upper(s).find("HZ") != std::string::npos)
    p.fail(v, key, "'" + s + "': the frequency selections are " + names);
  const uint64_t us = p.duration_us(v, key);
  const bool ms = us % 1000 == 0 && us >= 1000 && us <= 15000;
  const bool tenths = g.tenths && us % 100 == 0 && us >= 100 && us <= 1500;
  if (!ms && !tenths)
    p.fail(v, key, "'" + s + "': " + g.name + " takes 1ms ... 15ms" +
                       (g.tenths ? ", 0.1ms ... 1.5ms (0.1ms steps) or a frequency: " + names : ""));
  return us * 1000;
}

void parse_interrupts(Parse& p, const YAML::Node& l, HscConfig& cfg) {
  if (!l.IsSequence()) p.fail(l, "counters.interrupts", "expected a list such as [X3+, X0-]");
  std::set<int> pins;
  for (const auto& e : l) {
    std::string s = p.str(e, "counters.interrupts");
    if (s.size() < 3 || (s.back() != '+' && s.back() != '-'))
      p.fail(e, "counters.interrupts", "'" + s + "': expected an input and an edge, e.g. X3+ or X3-");
    const bool falling = s.back() == '-';
    const int x = p.pin(YAML::Node(s.substr(0, s.size() - 1)), "counters.interrupts");
    if (!pins.count(x)) p.use(x, e, "counters.interrupts", "an external interrupt input");
    pins.insert(x);
    cfg.edge_interrupts.push_back(2 * x + (falling ? 1 : 0));
  }
}

void parse_capture(Parse& p, const YAML::Node& l, HscConfig& cfg) {
  if (!l.IsSequence()) p.fail(l, "counters.capture", "expected a list of inputs such as [X3, X17]");
  for (const auto& e : l) {
    const int x = p.main_input(e, "counters.capture");
    if (cfg.capture[x]) p.fail(e, "counters.capture", "X" + std::to_string(x) + " is listed twice");
    cfg.capture[x] = true;
  }
}

void parse_filters(Parse& p, const YAML::Node& m, HscConfig& cfg) {
  if (!m.IsMap()) p.fail(m, "counters.filters", "expected a mapping such as {X0-X3: 28kHz, X16-X23: 2ms}");
  for (const auto& kv : m) {
    const std::string name = Parse::upper(p.str(kv.first, "counters.filters"));
    const FilterGroup* g = nullptr;
    std::string groups;
    for (const auto& fg : filter_groups()) {
      if (name == fg.name) g = &fg;
      groups += std::string(groups.empty() ? "" : ", ") + fg.name;
    }
    if (!g) p.fail(kv.first, "counters.filters", "'" + name + "' is not a filter group; the groups are " + groups);
    const std::string key = "counters.filters." + std::string(g->name);
    const uint64_t ns = parse_filter(p, kv.second, key, *g);
    for (int x = g->first; x <= g->last; ++x) cfg.filter_ns[x] = ns;
  }
}

SourceDef parse_source(Parse& p, const YAML::Node& s, size_t index) {
  const std::string key = "counters.sources";
  p.only(s, key, {"name", "type", "a", "b", "hz", "rpm", "per_rev", "follow"});
  SourceDef d;
  d.name = s["name"] ? p.topic_name(s["name"], key + ".name", "pulse source") : "source" + std::to_string(index);
  const std::string type = s["type"] ? p.str(s["type"], key + ".type") : "pulses";
  if (type != "encoder" && type != "pulses") p.fail(s["type"], key + ".type", "expected encoder or pulses");
  if (!s["a"]) p.fail(s, key, "needs a: the input its (A) phase drives");
  d.pin_a = p.pin(s["a"], key + ".a");
  if (type == "encoder") {
    d.pin_b = s["b"] ? p.pin(s["b"], key + ".b") : d.pin_a + 1;
    if (d.pin_b > 15) p.fail(s, key, "an encoder needs two inputs");
  } else if (s["b"]) {
    p.fail(s["b"], key + ".b", "a pulse generator drives one input");
  }
  if (s["hz"]) d.hz = p.number(s["hz"], key + ".hz", -1e7, 1e7);
  else if (s["rpm"]) d.hz = p.number(s["rpm"], key + ".rpm", -1e9, 1e9) / 60.0 *
                            (s["per_rev"] ? p.number(s["per_rev"], key + ".per_rev", 1, 1e6) : 1.0);
  else p.fail(s, key, "needs hz: (periods per second) or rpm: (with per_rev:)");
  if (s["follow"]) {
    d.has_follow = true;
    d.follow = p.address(s["follow"], key + ".follow");
    if (d.follow.width != Width::Bit) p.fail(s["follow"], key + ".follow", "expected a discrete such as Y0");
  }
  return d;
}

void parse_edges(Parse& p, const YAML::Node& l, HscConfig& cfg) {
  if (!l.IsSequence()) p.fail(l, "counters.edges", "expected a list");
  for (const auto& s : l) {
    p.only(s, "counters.edges", {"x", "steps"});
    if (!s["x"] || !s["steps"] || !s["steps"].IsSequence()) p.fail(s, "counters.edges", "needs x: and steps:");
    const int x = p.pin(s["x"], "counters.edges.x");
    for (const auto& st : s["steps"]) {
      if (!st.IsSequence() || st.size() != 2) p.fail(st, "counters.edges.steps", "each step is [time, level]");
      cfg.edges.push_back({p.duration_us(st[0], "counters.edges.steps") * 1000, x,
                           p.boolean(st[1], "counters.edges.steps")});
    }
  }
  std::stable_sort(cfg.edges.begin(), cfg.edges.end(),
                   [](const ScheduledEdge& a, const ScheduledEdge& b) { return a.t_ns < b.t_ns; });
}

}  // namespace

HscConfig parse_hsc_config(const YAML::Node& node, const std::string& file) {
  HscConfig cfg;
  if (!node || node.IsNull()) return cfg;
  Parse p(file);
  p.only(node, "counters", {"hsc0", "hsc1", "hsc2", "hsc3", "hsc4", "hsc5", "hsc6", "hsc7", "interrupts",
                            "sources", "edges", "frequency_window", "publish_rate", "capture", "filters",
                            "pulse_measurement"});
  for (int n = 0; n < 8; ++n) {
    const YAML::Node c = node["hsc" + std::to_string(n)];
    if (c && !c.IsNull()) parse_counter(p, n, c, cfg.counters[n]);
  }
  if (node["interrupts"]) parse_interrupts(p, node["interrupts"], cfg);
  if (node["capture"]) parse_capture(p, node["capture"], cfg);
  if (node["filters"]) parse_filters(p, node["filters"], cfg);
  if (node["frequency_window"]) {
    cfg.frequency_window_us = p.duration_us(node["frequency_window"], "counters.frequency_window");
    if (cfg.frequency_window_us < 1000) p.fail(node["frequency_window"], "counters.frequency_window", "at least 1ms");
  }
  if (node["publish_rate"]) cfg.publish_rate_hz = p.number(node["publish_rate"], "counters.publish_rate", 0.1, 1000);
  if (node["sources"]) {
    const YAML::Node l = node["sources"];
    if (!l.IsSequence()) p.fail(l, "counters.sources", "expected a list");
    for (const auto& s : l) cfg.sources.push_back(parse_source(p, s, cfg.sources.size()));
  }
  if (node["edges"]) parse_edges(p, node["edges"], cfg);
  cfg.pulse = parse_pulse_measurement(node["pulse_measurement"], file, cfg.counters);
  return cfg;
}

}  // namespace hsc
}  // namespace plc_cell
