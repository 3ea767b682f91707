#include "plc_cell/scenario/cell_target.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "plc_cell/core/error.h"
#include "plc_cell/scenario/raw_value.h"

namespace plc_cell {
namespace scenario {

CellTarget::CellTarget(const std::string& cell_yaml, const std::string& program,
                       const std::vector<SettingOverride>& run) {
  CellOverrides o;
  o.program = program;
  o.run = run;
  owned_ = std::make_unique<Cell>(cell_yaml, o, Cell::Purpose::Simulate);
  cell_ = owned_.get();
  if (!cell_->plc().set_mode(RunMode::Run)) throw Error("cannot RUN: no program loaded");
}

CellTarget::~CellTarget() = default;

const Address& CellTarget::address(const std::string& name) {
  auto it = addresses_.find(name);
  if (it == addresses_.end()) it = addresses_.emplace(name, cell_->config().resolve(name)).first;
  return it->second;
}

uint64_t CellTarget::period_us() const { return cell_->scan_period_us(); }

void CellTarget::scan(uint64_t t_us) {
  cell_->plc().scan(t_us);
  if (after_scan_) after_scan_(t_us);
}

const ProbeFacet* CellTarget::facet(SoftCell& cell, const Probe& p) {
  for (const auto& x : cell.extensions()) {
    const ProbeFacet* f = x->get<ProbeFacet>();
    if (!f) continue;
    const auto fs = f->families();
    if (std::find(fs.begin(), fs.end(), p.family) != fs.end()) return f;
  }
  return nullptr;
}

std::string CellTarget::check(const Probe& p, bool writing) {
  try {
    if (p.kind == Probe::Kind::Address) {
      const Address a = cell_->config().resolve(p.name);
      check_format(a, p.format, p.text);
      return "";
    }
    const ProbeFacet* f = facet(cell_->soft(), p);
    if (!f) return p.text + ": no extension of the cell reads '" + p.family + ".'";
    return f->check(plc(), p.ref(), writing);
  } catch (const Error& e) {
    return e.what();
  }
}

Reading CellTarget::read(const Probe& p) {
  if (p.kind == Probe::Kind::Address) {
    const Address a = address(p.name);
    const uint32_t v = plc().locked([&](ScanEngine&, Memory& m) { return m.read(a); });
    return address_reading(a, v, p.format);
  }
  if (const ProbeFacet* f = facet(cell_->soft(), p)) return f->read(plc(), p.ref());
  Reading r;
  r.valid = false;
  r.text = "?";
  return r;
}

void CellTarget::set(const Probe& p, const Value& v) {
  SoftCell& s = cell_->soft();
  if (p.kind == Probe::Kind::Address) {
    const Address a = address(p.name);
    const uint32_t x = raw_value(a, p.format, v, p.text);
    if (a.area == Area::X && a.width == Width::Bit) {
      // An input terminal: the scenario plays this sensor from now on, not the simulation.
      plc().locked([&](ScanEngine& e, Memory&) {
        s.simulation().override_input(a.index);
        e.set_input(a.index, x != 0);
        return 0;
      });
      return;
    }
    plc().write(a, {x});
    return;
  }
  const ProbeFacet* f = facet(s, p);
  if (!f) throw Error(p.text + ": no extension of the cell reads '" + p.family + ".'");
  const ProbeInput in{v.number, v.has_unit, v.number, v.unit, v.text};
  f->drive(plc(), p.ref(), in);
  // A stimulus acts on the extension, not on memory or the inputs: the lockstep twin's too.
  if (SoftCell* twin = cell_->twin()) facet(*twin, p)->drive(twin->plc(), p.ref(), in);
}

void CellTarget::write(const Probe& p, const Value& v) {
  if (p.kind != Probe::Kind::Address) throw Error(p.text + ": only an address or signal is written");
  const Address a = address(p.name);
  plc().write(a, {raw_value(a, p.format, v, p.text)});
}

void CellTarget::force(const Probe& p, bool on) {
  const Address a = address(p.name);
  if (a.width != Width::Bit || !is_discrete(a.area)) throw Error(p.text + ": only a single discrete is forced");
  plc().force(a, ForceAction::Disable);
  plc().force(a, on ? ForceAction::Set : ForceAction::Reset);
}

void CellTarget::release(const Probe* p) {
  std::vector<Address> points;
  if (p) points.push_back(address(p->name));
  else points = plc().locked([](ScanEngine&, Memory& m) { return m.disabled_points(); });
  for (const Address& a : points) plc().force(a, ForceAction::Enable);
}

void CellTarget::simulate(const Probe* p) {
  SoftCell& s = cell_->soft();
  if (!p) {
    plc().locked([&](ScanEngine&, Memory&) {
      for (uint32_t x : s.simulation().simulated_inputs()) s.simulation().resume(x);
      return 0;
    });
    return;
  }
  const Address a = address(p->name);
  if (a.area != Area::X || a.width != Width::Bit) throw Error(p->text + ": only an input (X) is simulated");
  const bool ok = plc().locked([&](ScanEngine&, Memory&) { return s.simulation().resume(a.index); });
  if (!ok) throw Error(p->text + ": the cell's simulation: has no signal on " + format_address(a));
}

std::string CellTarget::fault() {
  return plc().locked([](ScanEngine& e, Memory&) { return e.fault(); });
}

}  // namespace scenario
}  // namespace plc_cell
