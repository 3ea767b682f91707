#include "sections.h"

#include "plc_cell/scenario/property.h"

namespace plc_cell {
namespace scenario {

namespace {

Property read_property(const YamlReader& r, const YAML::Node& n, const std::string& key, Naming naming) {
  if (!n.IsMap()) r.fail(n, key, "a property is a mapping: {never: CONDITION} or {always: [A ->] B}");
  r.only(n, key, {"never", "always", "within"});
  if (bool(n["never"]) == bool(n["always"])) r.fail(n, key, "a property has one of 'never' and 'always'");
  const bool never = bool(n["never"]);
  const std::string k = key + (never ? ".never" : ".always");
  const YAML::Node c = n[never ? "never" : "always"];
  const std::string text = r.str(c, k);
  Property p = r.checked(c, k, [&] { return parse_property(never, text, naming); });
  p.file = r.file();
  p.line = YamlReader::line(n);
  if (n["within"]) p.within_us = r.duration_us(n["within"], key + ".within");
  return p;
}

InputDomain read_domain(const YamlReader& r, const YAML::Node& name, const YAML::Node& n, const std::string& key,
                        Naming naming) {
  InputDomain d;
  d.line = YamlReader::line(name);
  d.probe = r.checked(name, key, [&] { return parse_probe(name.Scalar(), naming); });
  if (d.probe.kind != Probe::Kind::Address) r.fail(name, key, "explore drives addresses and signals");
  if (!n.IsMap()) r.fail(n, key, "expected {hold: [SHORTEST, LONGEST]} and optionally values: [LOW, HIGH]");
  r.only(n, key, {"values", "hold"});
  if (!n["hold"]) r.fail(n, key, "missing 'hold': [SHORTEST, LONGEST] time a value is held (the shortest pulse)");
  const YAML::Node h = n["hold"];
  if (!h.IsSequence() || h.size() != 2) r.fail(h, key + ".hold", "expected [SHORTEST, LONGEST], e.g. [50ms, 2s]");
  d.hold_min_us = r.duration_us(h[0], key + ".hold[0]");
  d.hold_max_us = r.duration_us(h[1], key + ".hold[1]");
  if (d.hold_min_us == 0 || d.hold_min_us > d.hold_max_us)
    r.fail(h, key + ".hold", "the shortest hold must be above 0 and not above the longest");
  if (n["values"]) {
    const YAML::Node v = n["values"];
    if (!v.IsSequence() || v.size() != 2) r.fail(v, key + ".values", "expected [LOW, HIGH], e.g. [0, 100]");
    d.lo = double(r.integer(v[0], key + ".values[0]", -2147483648LL, 4294967295LL));
    d.hi = double(r.integer(v[1], key + ".values[1]", -2147483648LL, 4294967295LL));
    if (d.lo >= d.hi) r.fail(v, key + ".values", "LOW must be below HIGH");
  }
  return d;
}

}  // namespace

std::vector<Property> read_properties(const YamlReader& r, const YAML::Node& list, ErrorList& errors, Naming naming) {
  std::vector<Property> out;
  if (!list) return out;
  if (!list.IsSequence() || list.size() == 0) {
    errors.add(ErrorList::diagnostic(r.file(), list, "key 'properties': expected a list of {never: ...} or {always: ...}"));
    return out;
  }
  for (size_t i = 0; i < list.size(); ++i)
    errors.collect([&] { out.push_back(read_property(r, list[i], "properties[" + std::to_string(i) + "]", naming)); },
                   r.file(), list[i]);
  return out;
}

ExploreSpec read_explore(const YamlReader& r, const YAML::Node& n, ErrorList& errors, Naming naming) {
  ExploreSpec e;
  if (!n) return e;
  e.line = YamlReader::line(n);
  errors.collect([&] {
    if (!n.IsMap()) r.fail(n, "explore", "expected a mapping with inputs, run, budget and seed");
    r.only(n, "explore", {"inputs", "run", "budget", "seed"});
    e.run_us = n["run"] ? r.duration_us(n["run"], "explore.run") : 10000000;
    e.budget_us = n["budget"] ? r.duration_us(n["budget"], "explore.budget") : 10 * e.run_us;
    if (n["seed"]) e.seed = uint64_t(r.integer(n["seed"], "explore.seed", 0, INT64_MAX));
    if (e.run_us == 0) r.fail(n["run"], "explore.run", "a run of 0 s explores nothing");
    const YAML::Node in = n["inputs"];
    if (!in || !in.IsMap() || in.size() == 0)
      r.fail(in ? in : n, "explore.inputs", "expected a mapping of inputs to their domains ({start_button: {hold: [50ms, 2s]}})");
    for (const auto& kv : in) {
      const std::string k = "explore.inputs." + kv.first.Scalar();
      errors.collect([&] { e.inputs.push_back(read_domain(r, kv.first, kv.second, k, naming)); }, r.file(), kv.first);
    }
  }, r.file(), n);
  return e;
}

}  // namespace scenario
}  // namespace plc_cell
