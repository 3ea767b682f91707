#include "plc_cell/explore/input_run.h"

#include <algorithm>
#include <cmath>

namespace plc_cell {
namespace explore {

namespace {

// splitmix64: the runs depend on the seed alone, not on a library's distribution code.
class Random {
 public:
  explicit Random(uint64_t seed) : s_(seed) {}
  uint64_t next() {
    uint64_t z = (s_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  // In [lo, hi].
  uint64_t between(uint64_t lo, uint64_t hi) { return hi <= lo ? lo : lo + next() % (hi - lo + 1); }

 private:
  uint64_t s_;
};

bool is_bit(const scenario::InputDomain& d) { return d.lo == 0 && d.hi == 1; }

}  // namespace

InputRun random_run(const scenario::ExploreSpec& spec, uint64_t seed, uint64_t period_us) {
  Random rnd(seed);
  InputRun run;
  run.end_us = spec.run_us;
  const uint64_t p = period_us ? period_us : 1;
  for (size_t i = 0; i < spec.inputs.size(); ++i) {
    const scenario::InputDomain& d = spec.inputs[i];
    // Whole periods, at least the shortest hold.
    const uint64_t lo = (d.hold_min_us + p - 1) / p, hi = std::max(lo, d.hold_max_us / p);
    double value = d.lo;
    for (uint64_t t = rnd.between(lo, hi) * p; t < spec.run_us; t += rnd.between(lo, hi) * p) {
      if (is_bit(d)) {
        value = 1 - value;
      } else {
        const auto span = uint64_t(d.hi - d.lo);
        double v = d.lo + double(rnd.between(0, span - 1));
        value = v >= value ? v + 1 : v;  // another value than the current one
      }
      run.changes.push_back({t, i, value});
    }
  }
  std::stable_sort(run.changes.begin(), run.changes.end(), [](const Change& a, const Change& b) {
    return a.t_us != b.t_us ? a.t_us < b.t_us : a.input < b.input;
  });
  return run;
}

bool respects_domains(const scenario::ExploreSpec& spec, const InputRun& run) {
  std::vector<uint64_t> last(spec.inputs.size(), 0);
  uint64_t prev = 0;
  for (const Change& c : run.changes) {
    if (c.t_us < prev || c.input >= spec.inputs.size()) return false;
    const scenario::InputDomain& d = spec.inputs[c.input];
    if (c.t_us - last[c.input] < d.hold_min_us || c.value < d.lo || c.value > d.hi) return false;
    last[c.input] = c.t_us;
    prev = c.t_us;
  }
  return true;
}

void drop_no_ops(const scenario::ExploreSpec& spec, InputRun* run) {
  std::vector<double> value;
  for (const auto& d : spec.inputs) value.push_back(d.lo);
  std::vector<Change> kept;
  for (const Change& c : run->changes) {
    if (c.value == value[c.input]) continue;
    value[c.input] = c.value;
    kept.push_back(c);
  }
  run->changes = kept;
}

std::string value_text(const scenario::InputDomain& d, double v) {
  if (is_bit(d)) return v != 0 ? "on" : "off";
  return std::to_string(std::llround(v));
}

scenario::Case as_case(const scenario::Scenario& sc, const InputRun& run, const std::string& name) {
  scenario::Case c;
  c.name = name;
  c.file = sc.file;
  c.line = sc.explore.line;
  c.properties = sc.properties;
  auto assign = [&](scenario::Step& s, size_t input, double v) {
    scenario::Assignment a;
    a.target = sc.explore.inputs[input].probe;
    a.value.number = v;
    a.value.text = value_text(sc.explore.inputs[input], v);
    a.line = sc.explore.inputs[input].line;
    s.assignments.push_back(a);
  };
  auto step = [&](scenario::Step::Kind kind, const char* key) {
    scenario::Step s;
    s.kind = kind;
    s.key = key;
    s.file = sc.file;
    s.line = sc.explore.line;
    return s;
  };
  scenario::Step first = step(scenario::Step::Kind::Set, "set");
  for (size_t i = 0; i < sc.explore.inputs.size(); ++i) assign(first, i, sc.explore.inputs[i].lo);
  c.steps.push_back(first);
  for (const Change& ch : run.changes) {
    if (c.steps.back().has_at && c.steps.back().at_us == ch.t_us) {
      assign(c.steps.back(), ch.input, ch.value);
      continue;
    }
    scenario::Step s = step(scenario::Step::Kind::Set, "set");
    s.has_at = true;
    s.at_us = ch.t_us;
    assign(s, ch.input, ch.value);
    c.steps.push_back(s);
  }
  scenario::Step end = step(scenario::Step::Kind::Wait, "at");
  end.has_at = true;
  end.at_us = run.end_us;
  c.steps.push_back(end);
  return c;
}

}  // namespace explore
}  // namespace plc_cell
