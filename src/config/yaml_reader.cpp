#include "plc_cell/config/yaml_reader.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>

#include <yaml-cpp/depthguard.h>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/error_list.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/file_text.h"
#include "plc_cell/core/utf8.h"
#include "plc_cell/io/serial_settings.h"

namespace plc_cell {

static std::string listed(const std::set<std::string>& names) {
  std::string list;
  for (const auto& a : names) list += (list.empty() ? "" : ", ") + a;
  return list;
}

static std::string fmt(double v) {
  std::string s = std::to_string(v);
  s.erase(s.find_last_not_of('0') + 1);
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

void YamlReader::fail(const YAML::Node& n, const std::string& key, const std::string& msg) const {
  const YAML::Mark m = n.Mark();
  throw SourceError::at(file_, m.line >= 0 ? m.line + 1 : 0, m.column >= 0 ? m.column + 1 : 0,
                        "key '" + key + "': " + msg);
}

// yaml-cpp reports its recursion limit as "bad file": say what it is, with the limit.
static SourceError syntax_error(const std::string& file, const YAML::ParserException& e) {
  std::string why = e.msg;
  if (const auto* deep = dynamic_cast<const YAML::DeepRecursion*>(&e))
    why = "nesting too deep: more than " + std::to_string(deep->depth() - 1) +
          " levels of mappings and lists inside each other (the reader's limit)";
  return SourceError::at(file, e.mark.line + 1, e.mark.column + 1, "YAML syntax: " + why);
}

// YAML is Unicode text of printable characters (YAML 1.2, 5.1), here read as UTF-8.
// yaml-cpp would take any bytes and pass them on into names that reports (JUnit XML, the
// topics) must carry, so other bytes are refused where they are, as a syntax error is.
static void check_text(const std::string& file, const std::string& text) {
  int line = 1, column = 1;
  for (size_t i = 0; i < text.size(); ++column) {
    const size_t at = i;
    const char32_t c = utf8::next(text, &i);
    char why[160] = "";
    if (c == utf8::kInvalid) {
      std::snprintf(why, sizeof why, "not UTF-8: byte 0x%02X (a YAML file is Unicode text, read as UTF-8)",
                    static_cast<unsigned>(static_cast<unsigned char>(text[at])));
    } else if (!(c == '\t' || c == '\n' || c == '\r' || (c >= 0x20 && c <= 0x7E) || c == 0x85 ||
                 (c >= 0xA0 && c <= 0xD7FF) || (c >= 0xE000 && c <= 0xFFFD) || c >= 0x10000)) {
      std::snprintf(why, sizeof why,
                    "character U+%04X is not allowed in YAML text (a control character: in double quotes, "
                    "write it as an escape such as \\x07)",
                    static_cast<unsigned>(c));
    }
    if (why[0]) throw SourceError::at(file, line, column, why);
    if (c == '\n') ++line, column = 0;
  }
}

YAML::Node YamlReader::load(const std::string& text) const {
  check_text(file_, text);
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw syntax_error(file_, e);
  }
}

YAML::Node YamlReader::load_file(const std::string& path) {
  const std::optional<std::string> text = file_text(path);
  if (!text) throw Error(path + ": cannot read the file: " + std::strerror(errno));
  return YamlReader(path).load(*text);
}

void YamlReader::only(const YAML::Node& map, const std::string& key, const std::set<std::string>& allowed) const {
  if (!map.IsMap()) fail(map, key, "expected a mapping");
  for (const auto& kv : map) {
    const std::string k = kv.first.as<std::string>();
    if (!allowed.count(k))
      fail(kv.first, key.empty() ? k : key + "." + k, "unknown key (expected one of: " + listed(allowed) + ")");
  }
}

void YamlReader::only(const YAML::Node& map, const std::string& key, const std::set<std::string>& allowed,
                      ErrorList* errors) const {
  if (!map.IsMap()) fail(map, key, "expected a mapping");
  for (const auto& kv : map) {
    errors->collect([&] {
      const std::string k = kv.first.as<std::string>();
      if (allowed.count(k)) return;
      fail(kv.first, key.empty() ? k : key + "." + k, "unknown key (expected one of: " + listed(allowed) + ")");
    }, file_, kv.first);
  }
}

std::string YamlReader::str(const YAML::Node& n, const std::string& key) const {
  if (!n.IsScalar()) fail(n, key, "expected a single value");
  return n.as<std::string>();
}

std::string YamlReader::choice(const YAML::Node& n, const std::string& key,
                               const std::set<std::string>& allowed) const {
  const std::string v = n.IsScalar() ? n.as<std::string>() : "";
  if (!allowed.count(v)) fail(n, key, "expected one of: " + listed(allowed));
  return v;
}

double YamlReader::number(const YAML::Node& n, const std::string& key, double lo, double hi) const {
  double v = 0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    fail(n, key, "expected a number");
  }
  if (!(v >= lo && v <= hi) || std::isnan(v))
    fail(n, key, "value " + n.as<std::string>() + " out of range [" + fmt(lo) + ", " + fmt(hi) + "]");
  return v;
}

int64_t YamlReader::integer(const YAML::Node& n, const std::string& key, int64_t lo, int64_t hi) const {
  int64_t v = 0;
  try {
    v = n.as<int64_t>();
  } catch (const YAML::Exception&) {
    fail(n, key, "expected a whole number");
  }
  if (v < lo || v > hi) fail(n, key, "value out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v;
}

uint64_t YamlReader::seconds_us(const YAML::Node& n, const std::string& key, double lo_s, double hi_s) const {
  return static_cast<uint64_t>(std::llround(number(n, key, lo_s, hi_s) * 1e6));
}

uint64_t YamlReader::duration_us(const YAML::Node& n, const std::string& key) const {
  const std::string text = str(n, key);
  return checked(n, key, [&] { return parse_duration_us(text); });
}

bool YamlReader::boolean(const YAML::Node& n, const std::string& key) const {
  const std::string s = str(n, key);
  if (s == "1" || s == "true" || s == "on") return true;
  if (s == "0" || s == "false" || s == "off") return false;
  fail(n, key, "expected 0/1 or true/false");
}

Address YamlReader::address(const YAML::Node& n, const std::string& key) const {
  Address a;
  std::string why;
  if (!try_parse_address(str(n, key), &a, &why)) fail(n, key, "bad address " + why);
  return a;
}

AreaRange YamlReader::range(const YAML::Node& n, const std::string& key) const {
  const std::string s = str(n, key);
  const auto dash = s.find('-');
  Address a, b;
  std::string why;
  if (dash == std::string::npos) {
    if (!try_parse_address(s, &a, &why)) fail(n, key, "bad range '" + s + "': " + why);
    return {a.area, a.index, a.index};
  }
  if (!try_parse_address(s.substr(0, dash), &a, &why) || !try_parse_address(s.substr(dash + 1), &b, &why))
    fail(n, key, "bad range '" + s + "': " + why);
  if (a.area != b.area || a.width != b.width || b.index < a.index)
    fail(n, key, "bad range '" + s + "': both ends must name the same area, low end first (e.g. M800-M1399)");
  return {a.area, a.index, b.index};
}

Address YamlReader::data_register(const YAML::Node& n, const std::string& key) const {
  const Address a = address(n, key);
  if (a.width != Width::Word || (a.area != Area::R && a.area != Area::D)) fail(n, key, "expected an R or D register");
  return a;
}

std::string YamlReader::host_port(const YAML::Node& n, const std::string& key) const {
  const std::string v = str(n, key);
  checked(n, key, [&] {
    std::string host;
    int port = 0;
    parse_host_port(v, &host, &port);
  });
  return v;
}

std::string YamlReader::serial_line(const YAML::Node& n, const std::string& key, const char* format) const {
  const std::string v = str(n, key);
  checked(n, key, [&] { parse_serial_settings(v, format); });
  return v;
}

std::string YamlReader::topic_name(const YAML::Node& n, const std::string& key, const std::string& what) const {
  const std::string name = str(n, key);
  bool ok = !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0]));
  for (char c : name) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
  const bool vowel = !what.empty() && std::string("aeiou").find(what[0]) != std::string::npos;
  if (!ok) fail(n, key, (vowel ? "an " : "a ") + what + " name is letters, digits and _ (it becomes a ROS topic name)");
  return name;
}

std::vector<std::pair<std::string, Address>> YamlReader::discretes(const YAML::Node& map,
                                                                   const std::string& key) const {
  if (!map.IsMap()) fail(map, key, "expected a mapping of names to addresses (part_present: X3)");
  std::vector<std::pair<std::string, Address>> out;
  std::set<std::string> seen;
  for (const auto& kv : map) {
    const std::string k = key + "." + kv.first.as<std::string>();
    const std::string name = topic_name(kv.first, k, "signal");
    if (!seen.insert(name).second) fail(kv.first, k, "signal defined twice");
    const Address a = address(kv.second, k);
    if (a.width != Width::Bit) fail(kv.second, k, "a signal is a single discrete (X, Y, M, S, T, C)");
    out.emplace_back(name, a);
  }
  return out;
}

}  // namespace plc_cell
