#include "plc_cell/config/register_groups.h"

#include <cstdlib>
#include <set>

#include "plc_cell/core/error.h"

namespace plc_cell {

RegisterSpan parse_register_span(const std::string& text, const AddressParser& parse) {
  RegisterSpan s;
  const auto colon = text.find(':');
  s.start = parse ? parse(text.substr(0, colon)) : parse_address(text.substr(0, colon));
  if (colon != std::string::npos) {
    const std::string n = text.substr(colon + 1);
    char* end = nullptr;
    const long v = std::strtol(n.c_str(), &end, 10);
    if (n.empty() || *end || v < 1 || v > 100000) throw Error("'" + text + "': bad count (1-100000 after ':')");
    s.count = uint32_t(v);
  }
  check_span(s.start, s.count);
  return s;
}

std::vector<RegisterGroup> parse_register_groups(const YAML::Node& seq, const std::string& key,
                                                 const YamlReader& r, const AddressParser& parse) {
  if (!seq.IsSequence()) r.fail(seq, key, "expected a list of {name, rate, points}");
  std::vector<RegisterGroup> groups;
  std::set<std::string> seen;
  for (size_t i = 0; i < seq.size(); ++i) {
    const YAML::Node g = seq[i];
    const std::string at = key + "[" + std::to_string(i) + "]";
    r.only(g, at, {"name", "rate", "points"});
    RegisterGroup grp;
    if (!g["name"]) r.fail(g, at, "missing 'name'");
    grp.name = r.topic_name(g["name"], at + ".name", "group");
    if (!seen.insert(grp.name).second) r.fail(g["name"], at + ".name", "group '" + grp.name + "' defined twice");
    if (g["rate"]) grp.rate_hz = r.number(g["rate"], at + ".rate", 0.01, 100);
    const YAML::Node pts = g["points"];
    if (!pts || !pts.IsSequence() || pts.size() == 0)
      r.fail(pts ? pts : g, at + ".points", "expected a non-empty list of ADDRESS or ADDRESS:COUNT");
    for (size_t k = 0; k < pts.size(); ++k) {
      const std::string pk = at + ".points[" + std::to_string(k) + "]";
      const std::string text = r.str(pts[k], pk);
      try {
        grp.spans.push_back(parse_register_span(text, parse));
      } catch (const SourceError&) {
        throw;
      } catch (const Error& e) {
        r.fail(pts[k], pk, e.what());
      }
      grp.text += (grp.text.empty() ? "" : ",") + text;
    }
    groups.push_back(std::move(grp));
  }
  return groups;
}

}  // namespace plc_cell
