// The wires of a line checked against its cells (docs/lines.md, "Errors"): each end a
// signal or an address of a cell of the line, the sink one the wire may drive, one wire
// per sink, bits to bits and registers to registers of their width.
#include <algorithm>

#include "diagnostic_at.h"
#include "plc_cell/line/line.h"
#include "plc_cell/sim/virtual_run.h"

namespace plc_cell {
namespace line {

namespace {

// The first and last word or bit a's value takes in its area.
std::pair<uint32_t, uint32_t> span_of(const Address& a) {
  if (is_discrete(a.area)) return {a.index, a.index + (a.width == Width::Bit ? 0 : a.width == Width::Word ? 15 : 31)};
  return {a.index, a.index + (a.width == Width::DWord ? 1 : 0)};
}

// Why a wire may not drive a (as its cell names it: text), or "".
std::string refused_sink(const Address& a, const std::string& text) {
  const std::string what = "'" + text + "' (" + format_address(a) + ")";
  const std::string may = ": a wire drives an input (X), a relay (M, S) or a register (R, D)";
  switch (a.area) {
    case Area::Y: return what + " is an output" + may;
    case Area::T: case Area::C: return what + " is a timer or counter contact" + may;
    case Area::RT: case Area::RC: return what + " is a timer or counter value" + may;
    case Area::F: return what + " is a file register" + may;
    default: break;
  }
  if (is_discrete(a.area) && a.width != Width::Bit)
    return what + " is 16 or 32 points: a wire drives one input or relay";
  if (a.area == Area::M && a.index >= special::kFirstSpecialM) return what + " is a special relay of the PLC";
  if (a.area == Area::R && a.index + (a.width == Width::DWord ? 1 : 0) >= 3840)
    return what + " is a special or read-only register (R3840 and up)";
  return "";
}

}  // namespace

// One end of a wire: its cell (built or read) and its address there; false (with the
// error, unless the cell's YAML has errors of its own) when there is none.
bool Line::resolve_end(const std::vector<const CellConfig*>& configs, const std::string& text,
                       const SourceLocation& at, size_t* cell, Address* a, ErrorList& errors) const {
  std::string name, rest;
  split_qualified(text, &name, &rest);
  const int i = find(name);
  if (i < 0) {
    errors.add(error_at(at, "'" + text + "': no cell '" + name + "' in the line (" + names() + ")"));
    return false;
  }
  *cell = size_t(i);
  if (!configs[*cell]) return false;
  try {
    *a = configs[*cell]->resolve(rest);
  } catch (const Error& x) {
    errors.add(error_at(at, "'" + text + "': " + x.what()));
    return false;
  }
  return true;
}

// Why the wire, its ends resolved, may not be (at its place), or an empty message.
Diagnostic Line::refused_wire(const Wire& w, const CellConfig& to_cfg) {
  const WireEntry& e = w.entry;
  const std::string why = refused_sink(w.to, e.to);
  if (!why.empty()) return error_at(e.to_at, why);
  const int from_bits = value_bits(w.from), to_bits = value_bits(w.to);
  const auto bits = [](int n) { return n == 1 ? std::string("a bit") : std::to_string(n) + " bits"; };
  if (from_bits != to_bits)
    return error_at(e.to_at, "'" + e.from + "' is " + bits(from_bits) + ", '" + e.to + "' " + bits(to_bits) +
                                 ": a wire joins a bit to a bit, a register to a register of its width");
  if (from_bits != 1 && (e.invert || e.part))
    return error_at(e.at, std::string("a register's wire carries its value: '") + (e.invert ? "invert" : "part") +
                              "' is for a bit");
  if (w.to.area != Area::X) return {};
  const auto sim = std::find_if(to_cfg.sim_inputs.begin(), to_cfg.sim_inputs.end(),
                                [&](const SimInputDef& d) { return d.x == w.to.index; });
  if (sim != to_cfg.sim_inputs.end())
    return error_at(e.to_at, "'" + e.to + "' (" + format_address(w.to) + ") is played by the simulation of " +
                                 to_cfg.file + " (simulation.inputs." + sim->name +
                                 "): a wired input has no simulation of its own");
  Cell* c = cells_[w.to_cell].get();
  if (c && w.to.index < 16 &&
      !c->plc().locked([&](ScanEngine&, Memory&) { return c->soft().simulation().exact(w.to.index); }))
    return error_at(e.to_at, "'" + e.to + "' (" + format_address(w.to) +
                                 ") is driven by a pulse source of the cell's counters or axes");
  return {};
}

void Line::resolve_wires(const std::vector<const CellConfig*>& configs, ErrorList& errors) {
  struct Driven {
    size_t cell;
    Address a;
    int line;
  };
  std::vector<Driven> driven;
  for (const WireEntry& e : file_.wires) {
    Wire w;
    w.entry = e;
    const bool from = resolve_end(configs, e.from, e.from_at, &w.from_cell, &w.from, errors);
    if (!resolve_end(configs, e.to, e.to_at, &w.to_cell, &w.to, errors) || !from) continue;
    const Diagnostic refused = refused_wire(w, *configs[w.to_cell]);
    if (!refused.message.empty()) {
      errors.add(refused);
      continue;
    }
    const auto [lo, hi] = span_of(w.to);
    const auto twice = std::find_if(driven.begin(), driven.end(), [&](const Driven& d) {
      const auto [dlo, dhi] = span_of(d.a);
      return d.cell == w.to_cell && d.a.area == w.to.area && dlo <= hi && lo <= dhi;
    });
    if (twice != driven.end()) {
      errors.add(error_at(e.to_at, "'" + e.to + "' (" + format_address(w.to) + ") is driven already, by the wire at " +
                                       file_.file + ":" + std::to_string(twice->line)));
      continue;
    }
    driven.push_back({w.to_cell, w.to, e.at.line});
    w.model.delay_ns = e.delay_us * 1000;
    w.model.invert = e.invert;
    w.model.part = e.part;
    w.model.travel_ns = e.travel_us * 1000;
    w.model.length_ns = e.length_us * 1000;
    wires_.push_back(w);
  }
}

}  // namespace line
}  // namespace plc_cell
