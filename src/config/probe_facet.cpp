#include "plc_cell/config/probe_facet.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <set>

#include "plc_cell/core/error.h"

namespace plc_cell {

namespace {

struct ProbeFamilyList {
  std::mutex mu;
  uint64_t next = 0;
  std::vector<std::pair<uint64_t, ProbeFamily>> families;  // in the order registered
};

ProbeFamilyList& probe_family_list() {
  static ProbeFamilyList r;
  return r;
}

}  // namespace

void ProbeFacet::drive(Plc&, const ProbeRef& p, const ProbeInput&) const {
  throw Error(p.text + ": only an address or signal is written");
}

ProbeFamilyRegistration::ProbeFamilyRegistration(ProbeFamily family) {
  ProbeFamilyList& r = probe_family_list();
  std::lock_guard<std::mutex> lk(r.mu);
  id_ = r.next++;
  r.families.emplace_back(id_, std::move(family));
}

ProbeFamilyRegistration::~ProbeFamilyRegistration() {
  ProbeFamilyList& r = probe_family_list();
  std::lock_guard<std::mutex> lk(r.mu);
  for (auto it = r.families.begin(); it != r.families.end(); ++it)
    if (it->first == id_) {
      r.families.erase(it);
      return;
    }
}

std::optional<ProbeFamily> registered_probe_family(const std::string& name) {
  ProbeFamilyList& r = probe_family_list();
  std::lock_guard<std::mutex> lk(r.mu);
  for (auto it = r.families.rbegin(); it != r.families.rend(); ++it)
    if (it->second.name == name) return it->second;
  return std::nullopt;
}

std::vector<std::string> registered_probe_families() {
  ProbeFamilyList& r = probe_family_list();
  std::lock_guard<std::mutex> lk(r.mu);
  std::set<std::string> names;
  for (const auto& f : r.families) names.insert(f.second.name);
  return {names.begin(), names.end()};
}

std::string stimulus_units(const ProbeFamily& f) {
  std::string out;
  for (size_t i = 0; i < f.stimuli.size(); ++i)
    out += (i == 0 ? "" : i + 1 == f.stimuli.size() ? " or " : ", ") + f.stimuli[i].spellings.at(0);
  return out;
}

ProbeInput parse_stimulus(const ProbeFamily& f, const std::string& text) {
  const std::string takes = (f.what.empty() ? f.name + "." : f.what) + " takes " + stimulus_units(f);
  const char* s = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(s, &end);
  if (end == s || !std::isfinite(v)) throw Error("'" + text + "' is not a number with a unit: " + takes);
  std::string unit(end);
  while (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
  while (!unit.empty() && unit.back() == ' ') unit.pop_back();
  if (unit.empty()) throw Error("'" + text + "' has no unit: " + takes);
  for (const StimulusUnit& u : f.stimuli)
    for (const std::string& w : u.spellings)
      if (w == unit) return ProbeInput{v * u.factor, true, v * u.factor, u.unit, text};
  throw Error(takes + ", not " + unit);
}

std::string probe_number_text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

}  // namespace plc_cell
