#include "plc_cell/scenario/line_wall_clock.h"

#include <algorithm>

#include "plc_cell/scenario/runner.h"

namespace plc_cell {
namespace scenario {

Resolution worst_resolution(const std::vector<Resolution>& rs) {
  Resolution worst;
  for (const auto& r : rs)
    if (r.us() > worst.us() || worst.polls == 0) worst = r;
  return worst;
}

std::vector<Address> polled_in(const LineCellLink& cell, const std::vector<Case>& cases) {
  std::vector<Address> polled;
  if (!cell.plc) return polled;
  WallClockOptions o;
  o.cell = cell.name;
  for (const auto& c : cases) {
    const WallClockTarget t(*cell.plc, *cell.config, c, o);
    for (const Address& a : t.polled_addresses())
      if (std::find(polled.begin(), polled.end(), a) == polled.end()) polled.push_back(a);
  }
  return polled;
}

std::vector<TouchedPoint> touched_in(const LineCellLink& cell, const std::vector<Case>& cases) {
  std::vector<TouchedPoint> all;
  if (!cell.config) return all;
  for (const auto& c : cases)
    for (const auto& p : touched_points(c, *cell.config, cell.name))
      if (std::none_of(all.begin(), all.end(), [&](const TouchedPoint& t) { return t.address == p.address; }))
        all.push_back(p);
  return all;
}

std::vector<Diagnostic> refusals_on_line(const std::vector<LineCellLink>& cells, const std::string& target,
                                         const Scenario& sc, const WallClockRules& rules, std::vector<Case>* cases,
                                         std::vector<StepNote>* widened) {
  std::vector<Diagnostic> errors;
  const std::string why = sc.hardware.refuses(target);
  if (!why.empty()) errors.push_back(at_hardware_key(sc, why));
  for (const auto& cell : cells) {
    if (!cell.plc || (polled_in(cell, *cases).empty() && touched_in(cell, *cases).empty())) continue;
    const std::string mode = mode_refusal(*cell.plc, sc);
    if (!mode.empty()) errors.push_back(at_hardware_key(sc, cell.name + ": " + mode));
  }
  const ConfigOf config_of = [&cells](const std::string& name) -> const CellConfig* {
    for (const auto& c : cells)
      if (c.name == name) return c.config;
    return nullptr;
  };
  for (Case& c : *cases) {
    LineWallClockTarget t(cells, c, {});
    for (auto& e : check_case(c, t)) errors.push_back(e);
    Preflight p = wall_clock_preflight(c, rules, config_of);
    errors.insert(errors.end(), p.errors.begin(), p.errors.end());
    if (widened) widened->insert(widened->end(), p.widened.begin(), p.widened.end());
    c = std::move(p.adjusted);
  }
  said_once(&errors, widened);
  return errors;
}

std::string forces_and_writes_on_line(const std::vector<LineCellLink>& cells, const std::vector<Case>& cases) {
  std::vector<TouchedPoint> all;
  for (const auto& cell : cells)
    for (const auto& p : touched_in(cell, cases)) all.push_back(p);
  return forces_and_writes(all);
}

}  // namespace scenario
}  // namespace plc_cell
