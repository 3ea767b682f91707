#include "plc_cell/config/server_kind.h"

#include <algorithm>
#include <sstream>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"
#include "plc_cell/io/serial_settings.h"

namespace plc_cell {
namespace {

std::string seconds(int64_t us) {
  std::ostringstream s;
  s << double(us) / 1e6;
  return s.str();
}

int64_t parse_integer(const std::string& text) {
  size_t pos = 0;
  long long v = 0;
  try {
    v = std::stoll(text, &pos, 10);
  } catch (const std::exception&) {
    pos = 0;
  }
  if (pos == 0 || pos != text.size()) throw Error("expected a whole number");
  return v;
}

}  // namespace

std::string check_setting(const SettingSpec& spec, const std::string& text) {
  switch (spec.type) {
    case SettingType::Text:
      return text;
    case SettingType::HostPort: {
      if (text.empty()) return text;
      std::string host;
      int port = 0;
      parse_host_port(text, &host, &port);
      return text;
    }
    case SettingType::SerialLine:
      if (!text.empty()) parse_serial_settings(text, spec.format);
      return text;
    case SettingType::Integer: {
      const int64_t v = parse_integer(text);
      if (v < spec.lo || v > spec.hi)
        throw Error("value out of range [" + std::to_string(spec.lo) + ", " + std::to_string(spec.hi) + "]");
      return std::to_string(v);
    }
    case SettingType::Duration: {
      uint64_t us = 0;
      try {
        us = parse_duration_us(text);
      } catch (const Error& e) {
        throw Error(std::string("expected a duration such as 60s or 250ms: ") + e.what());
      }
      if (int64_t(us) < spec.lo || int64_t(us) > spec.hi)
        throw Error("value out of range [" + seconds(spec.lo) + ", " + seconds(spec.hi) + "] s");
      return std::to_string(us) + "us";
    }
    case SettingType::Writable:
      WritableRanges::parse(text);
      return text;
    case SettingType::Boolean:
      if (text == "true" || text == "on" || text == "1") return "true";
      if (text == "false" || text == "off" || text == "0") return "false";
      throw Error("expected true or false");
  }
  return text;
}

SettingSpec setting(std::string key, SettingType type, std::string help, std::string fallback) {
  SettingSpec s;
  s.key = std::move(key), s.type = type, s.help = std::move(help), s.fallback = std::move(fallback);
  return s;
}

SettingSpec serial_setting(std::string key, std::string format, std::string help) {
  SettingSpec s = setting(std::move(key), SettingType::SerialLine, std::move(help));
  s.format = std::move(format);
  return s;
}

SettingSpec integer_setting(std::string key, int64_t fallback, int64_t lo, int64_t hi, std::string help) {
  SettingSpec s = setting(std::move(key), SettingType::Integer, std::move(help), std::to_string(fallback));
  s.lo = lo, s.hi = hi;
  return s;
}

SettingSpec duration_setting(std::string key, std::string fallback, int64_t lo_us, int64_t hi_us, std::string help) {
  SettingSpec s = setting(std::move(key), SettingType::Duration, std::move(help), std::move(fallback));
  s.lo = lo_us, s.hi = hi_us;
  return s;
}

std::vector<SettingSpec> client_limits(int max_connections) {
  return {setting("writable", SettingType::Writable,
                  "what clients may write: all, none, or ranges such as D0-D99,M800 (docs/security.md)", "all"),
          integer_setting("max_connections", max_connections, 1, 1024, "open TCP connections at most; one more is refused"),
          duration_setting("idle_timeout", "60s", 1000, 86400000000, "a TCP connection silent this long is closed (1ms-24h)")};
}

const std::string& Settings::text(const std::string& key) const {
  static const std::string none;
  const auto& v = all(key);
  return v.empty() ? none : v.front();
}

const std::vector<std::string>& Settings::all(const std::string& key) const {
  const auto it = values_.find(key);
  if (it == values_.end()) throw Error("server kind '" + kind_ + "' has no setting '" + key + "'");
  return it->second;
}

int64_t Settings::integer(const std::string& key) const { return parse_integer(text(key)); }
uint64_t Settings::duration_us(const std::string& key) const { return parse_duration_us(text(key)); }
WritableRanges Settings::writable(const std::string& key) const { return WritableRanges::parse(text(key)); }

const SettingSpec* ServerKind::spec(const std::string& key) const {
  for (const auto& s : settings)
    if (s.key == key) return &s;
  return nullptr;
}

std::string ServerKind::option(const SettingSpec& s) const {
  std::string o = "--" + name + "-" + s.key;
  std::replace(o.begin(), o.end(), '_', '-');
  return o;
}

std::string ServerKind::parameter(const SettingSpec& s) const { return "~" + name + "_" + s.key; }

std::map<std::string, Settings> merge_server_settings(const std::vector<ServerKind>& kinds, const CellConfig& cfg,
                                                      const std::vector<SettingOverride>& overrides) {
  std::map<std::string, std::map<std::string, std::vector<std::string>>> values;
  for (const auto& k : kinds)
    for (const auto& s : k.settings)
      values[k.name][s.key] = s.fallback.empty() ? std::vector<std::string>{} : std::vector<std::string>{s.fallback};

  // A cell without a file has no document: every setting keeps its default.
  const YAML::Node section = cfg.document.IsMap() ? cfg.document["servers"] : YAML::Node(YAML::NodeType::Undefined);
  if (section.IsDefined()) {
    const YamlReader r(cfg.file);
    std::set<std::string> names;
    for (const auto& k : kinds) names.insert(k.name);
    r.only(section, "servers", names);
    for (const auto& k : kinds) {
      const YAML::Node n = section[k.name];
      if (!n) continue;
      const std::string where = "servers." + k.name;
      std::set<std::string> keys;
      for (const auto& s : k.settings) keys.insert(s.key);
      r.only(n, where, keys);
      for (const auto& s : k.settings) {
        const YAML::Node v = n[s.key];
        if (!v) continue;
        const std::string key = where + "." + s.key;
        std::vector<std::string> texts;
        if (v.IsSequence() && s.type == SettingType::Writable) {
          std::string joined;
          for (size_t i = 0; i < v.size(); ++i) joined += (joined.empty() ? "" : ",") + r.str(v[i], key);
          texts.push_back(joined.empty() ? "none" : joined);
        } else if (v.IsSequence() && s.repeatable) {
          for (size_t i = 0; i < v.size(); ++i) texts.push_back(r.str(v[i], key));
        } else {
          texts.push_back(r.str(v, key));
        }
        for (auto& t : texts) t = r.checked(v, key, [&] { return check_setting(s, t); });
        values[k.name][s.key] = texts;
      }
    }
  }

  for (const auto& o : overrides) {
    const auto k = std::find_if(kinds.begin(), kinds.end(), [&](const ServerKind& x) { return x.name == o.kind; });
    const SettingSpec* s = k == kinds.end() ? nullptr : k->spec(o.key);
    if (!s) throw Error(o.origin + ": no server setting " + o.kind + "." + o.key);
    if (o.values.size() > 1 && !s->repeatable) throw Error(o.origin + ": given more than once");
    std::vector<std::string> texts;
    for (const auto& v : o.values) {
      try {
        texts.push_back(check_setting(*s, v));
      } catch (const Error& e) {
        throw Error(o.origin + " " + v + ": " + e.what());
      }
    }
    // An empty endpoint turns a server the YAML asks for off.
    if (texts.size() == 1 && texts[0].empty()) texts.clear();
    values[o.kind][o.key] = texts;
  }

  std::map<std::string, Settings> out;
  for (auto& kv : values) out.emplace(kv.first, Settings(kv.first, std::move(kv.second)));
  return out;
}

}  // namespace plc_cell
