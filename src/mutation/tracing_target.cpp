#include "tracing_target.h"

#include <cstring>
#include <set>

namespace plc_cell {
namespace mutation {

TracingTarget::TracingTarget(scenario::Target& inner, const scenario::Case& c) : inner_(inner) {
  for (int w = 0; w < 256; w += 16) probes_.push_back(scenario::parse_probe("WY" + std::to_string(w)));
  std::set<std::string> seen;
  auto add = [&](const scenario::Condition& cond) {
    for (const auto& cmp : cond.all)
      if (cmp.probe.kind != scenario::Probe::Kind::Analog && seen.insert(cmp.probe.text).second)
        probes_.push_back(cmp.probe);
  };
  for (const auto& s : c.steps) {
    add(s.cond);
    for (const auto& e : s.sequence) add(e.cond);
  }
  for (const auto& p : c.properties) {
    add(p.when);
    add(p.cond);
  }
}

void TracingTarget::scan(uint64_t t_us) {
  inner_.scan(t_us);
  for (const auto& p : probes_) {
    const scenario::Reading r = inner_.read(p);
    uint64_t bits;
    std::memcpy(&bits, &r.number, sizeof bits);
    for (int i = 0; i < 8; ++i) hash_ = (hash_ ^ ((bits >> (8 * i)) & 0xFF)) * 1099511628211ULL;
  }
}

}  // namespace mutation
}  // namespace plc_cell
