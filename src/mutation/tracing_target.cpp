#include "tracing_target.h"

#include <cstring>
#include <set>

namespace plc_cell {
namespace mutation {

scenario::Probe probe_of(const Subject::Part& part, const std::string& name) {
  return scenario::parse_probe(part.prefix + name, part.prefix.empty() ? scenario::Naming::Cell : scenario::Naming::Line);
}

std::vector<scenario::Probe> output_words(const Subject& s) {
  std::vector<scenario::Probe> out;
  for (const auto& part : s.cells)
    for (int w = 0; w < 256; w += 16) out.push_back(probe_of(part, "WY" + std::to_string(w)));
  return out;
}

std::vector<scenario::Probe> case_probes(const scenario::Case& c) {
  std::vector<scenario::Probe> out;
  std::set<std::string> seen;
  auto add = [&](const scenario::Condition& cond) {
    for (const auto& cmp : cond.all)
      for (const scenario::Probe* p : cmp.probes())
        if (p->kind != scenario::Probe::Kind::Analog && seen.insert(p->text).second) out.push_back(*p);
  };
  for (const auto& s : c.steps) {
    add(s.cond);
    for (const auto& e : s.sequence) add(e.cond);
  }
  for (const auto& p : c.properties) {
    add(p.when);
    add(p.cond);
  }
  return out;
}

uint64_t fold(uint64_t hash, scenario::Target& t, const std::vector<scenario::Probe>& probes) {
  auto byte = [&](uint64_t b) { hash = (hash ^ (b & 0xFF)) * 1099511628211ULL; };
  for (const auto& p : probes) {
    const scenario::Reading r = t.read(p);
    uint64_t bits;
    std::memcpy(&bits, &r.number, sizeof bits);
    for (int i = 0; i < 8; ++i) byte(bits >> (8 * i));
  }
  return hash;
}

TracingTarget::TracingTarget(scenario::Target& inner, const scenario::Case& c, std::vector<scenario::Probe> outputs)
    : inner_(inner), probes_(std::move(outputs)) {
  for (auto& p : case_probes(c)) probes_.push_back(p);
}

void TracingTarget::scan(uint64_t t_us) {
  inner_.scan(t_us);
  hash_ = fold(hash_, inner_, probes_);
}

}  // namespace mutation
}  // namespace plc_cell
