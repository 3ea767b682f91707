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

void Line::resolve_wires(const std::vector<CellConfig>& configs, ErrorList& errors) {
  struct Driven {
    size_t cell;
    Address a;
    int line;
  };
  std::vector<Driven> driven;
  for (const WireEntry& e : file_.wires) {
    Wire w;
    w.entry = e;
    bool ok = true;
    // One end: its cell (built or read) and its address there.
    auto end = [&](const std::string& text, const SourceLocation& at, size_t* cell, Address* a) {
      std::string name, rest;
      split_qualified(text, &name, &rest);
      const int i = find(name);
      if (i < 0) {
        errors.add(error_at(at, "'" + text + "': no cell '" + name + "' in the line (" + names() + ")"));
        return false;
      }
      *cell = size_t(i);
      if (configs[*cell].name.empty()) return false;  // its YAML has errors of its own
      try {
        *a = configs[*cell].resolve(rest);
      } catch (const Error& x) {
        errors.add(error_at(at, "'" + text + "': " + x.what()));
        return false;
      }
      return true;
    };
    ok = end(e.from, e.from_at, &w.from_cell, &w.from) & ok;
    ok = end(e.to, e.to_at, &w.to_cell, &w.to) & ok;
    if (!ok) continue;
    const std::string why = refused_sink(w.to, e.to);
    if (!why.empty()) {
      errors.add(error_at(e.to_at, why));
      continue;
    }
    const int from_bits = value_bits(w.from), to_bits = value_bits(w.to);
    if (from_bits != to_bits) {
      errors.add(error_at(e.to_at, "'" + e.from + "' is " + (from_bits == 1 ? "a bit" : std::to_string(from_bits) + " bits") +
                                       ", '" + e.to + "' " + (to_bits == 1 ? "a bit" : std::to_string(to_bits) + " bits") +
                                       ": a wire joins a bit to a bit, a register to a register of its width"));
      continue;
    }
    if (from_bits != 1 && (e.invert || e.part)) {
      errors.add(error_at(e.at, std::string("a register's wire carries its value: '") + (e.invert ? "invert" : "part") +
                                    "' is for a bit"));
      continue;
    }
    const CellConfig& to_cfg = configs[w.to_cell];
    if (w.to.area == Area::X) {
      const auto sim = std::find_if(to_cfg.sim_inputs.begin(), to_cfg.sim_inputs.end(),
                                    [&](const SimInputDef& d) { return d.x == w.to.index; });
      if (sim != to_cfg.sim_inputs.end()) {
        errors.add(error_at(e.to_at, "'" + e.to + "' (" + format_address(w.to) + ") is played by the simulation of " +
                                         to_cfg.file + " (simulation.inputs." + sim->name +
                                         "): a wired input has no simulation of its own"));
        continue;
      }
      Cell* c = cells_[w.to_cell].get();
      const bool pinned = c && w.to.index < 16 &&
                          !c->plc().locked([&](ScanEngine&, Memory&) { return c->soft().simulation().exact(w.to.index); });
      if (pinned) {
        errors.add(error_at(e.to_at, "'" + e.to + "' (" + format_address(w.to) +
                                         ") is driven by a pulse source of the cell's counters or axes"));
        continue;
      }
    }
    const auto [lo, hi] = span_of(w.to);
    const auto twice = std::find_if(driven.begin(), driven.end(), [&](const Driven& d) {
      const auto [dlo, dhi] = span_of(d.a);
      return d.cell == w.to_cell && is_discrete(d.a.area) == is_discrete(w.to.area) && d.a.area == w.to.area &&
             dlo <= hi && lo <= dhi;
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
