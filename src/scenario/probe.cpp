#include "plc_cell/scenario/probe.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace scenario {

namespace {

bool is_name(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

bool registered_family(const std::string& name) { return registered_probe_family(name).has_value(); }

std::string listed_families() {
  std::vector<std::string> all = {"counter", "axis", "temperature", "analog", "pulse"};
  for (const auto& n : registered_probe_families())
    if (std::find(all.begin(), all.end(), n) == all.end()) all.push_back(n);
  std::string out;
  for (size_t i = 0; i < all.size(); ++i) out += (i == 0 ? "" : i + 1 == all.size() ? " or " : ", ") + all[i] + ".";
  return out;
}

// FAMILY.NAME or FAMILY.NAME.FIELD of a registered family.
Probe extension_probe(const std::string& text, const std::string& family, const std::string& rest) {
  Probe p;
  p.text = text;
  p.kind = Probe::Kind::Extension;
  p.family = family;
  const auto dot = rest.find('.');
  p.name = rest.substr(0, dot);
  p.field = dot == std::string::npos ? "" : rest.substr(dot + 1);
  if (!is_name(p.name)) throw Error("'" + text + "': '" + p.name + "' is not a " + family + " name");
  if (dot != std::string::npos && !is_name(p.field)) throw Error("'" + text + "': '" + p.field + "' is not a field name");
  return p;
}

}  // namespace

std::string probe_label(const Probe& p, const CellConfig& cell) {
  if (p.kind != Probe::Kind::Address) return p.text;
  Address a;
  try {
    a = cell.resolve(p.name);
  } catch (const Error&) {
    return p.text;  // the target reports an unknown name before a case runs
  }
  for (const auto& s : cell.signals)
    if (s.second == a) return s.first + " (" + format_address(a) + ")";
  return p.text;
}

Reading address_reading(const Address& a, uint32_t v, ValueFormat f) {
  Reading r;
  const int bits = value_bits(a);
  if (bits == 1) {
    r.number = v;
    r.text = v ? "ON" : "OFF";
    return r;
  }
  r.text = format_value(a, v, f);
  if (f == ValueFormat::F32) {
    float x;
    std::memcpy(&x, &v, sizeof x);
    r.number = double(x);
    r.valid = std::isfinite(x);
  } else if (f == ValueFormat::Unsigned || f == ValueFormat::Hex || (f == ValueFormat::Default && is_discrete(a.area))) {
    r.number = double(v);
  } else {
    r.number = bits == 16 ? double(int16_t(uint16_t(v))) : double(int32_t(v));
  }
  return r;
}

Probe parse_probe(const std::string& text, Naming naming) {
  if (naming == Naming::Line) {
    const auto dot = text.find('.');
    if (dot == std::string::npos)
      throw Error("'" + text + "': a line's names start with their cell: CELL." + text);
    const std::string cell = text.substr(0, dot);
    if (!is_name(cell)) throw Error("'" + text + "': '" + cell + "' is not a cell name");
    Probe q = parse_probe(text.substr(dot + 1), Naming::Cell);
    q.cell = cell;
    q.text = text;
    return q;
  }
  Probe p;
  p.text = text;
  const auto dot = text.find('.');
  if (dot == std::string::npos) {
    // An address or a signal; which one is the cell's to say (target.check).
    const auto nf = split_format(text);
    if (!is_name(nf.first)) throw Error("'" + text + "' is not an address or a signal name");
    p.name = nf.first;
    p.format = nf.second;
    return p;
  }
  const std::string kind = text.substr(0, dot), rest = text.substr(dot + 1);
  if (kind == "counter" || kind == "temperature" || kind == "analog") {
    if (!is_name(rest)) throw Error("'" + text + "': '" + rest + "' is not a " + kind + " name");
    p.kind = kind == "counter" ? Probe::Kind::Counter
             : kind == "temperature" ? Probe::Kind::Temperature
                                     : Probe::Kind::Analog;
    p.name = rest;
    p.family = kind;
    return p;
  }
  if (kind == "axis") {
    const auto dot2 = rest.find('.');
    const std::string axis = rest.substr(0, dot2), what = dot2 == std::string::npos ? "" : rest.substr(dot2 + 1);
    if (!is_name(axis)) throw Error("'" + text + "': '" + axis + "' is not an axis name");
    if (what == "position") p.kind = Probe::Kind::AxisPosition;
    else if (what == "state") p.kind = Probe::Kind::AxisState;
    else if (what == "frequency") p.kind = Probe::Kind::AxisFrequency;
    else throw Error("'" + text + "': an axis is read as axis.NAME.position, .state or .frequency");
    p.name = axis;
    p.family = kind;
    p.field = what;
    return p;
  }
  if (kind == "pulse") {
    const auto dot2 = rest.find('.');
    std::string input = rest.substr(0, dot2);
    const std::string what = dot2 == std::string::npos ? "" : rest.substr(dot2 + 1);
    for (auto& c : input) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (input.size() < 2 || input[0] != 'X' || !std::all_of(input.begin() + 1, input.end(), ::isdigit))
      throw Error("'" + text + "': '" + input + "' is not an input such as X0");
    if (what == "width") p.kind = Probe::Kind::PulseWidth;
    else if (what == "period") p.kind = Probe::Kind::PulsePeriod;
    else if (what == "frequency") p.kind = Probe::Kind::PulseFrequency;
    else throw Error("'" + text + "': a pulse measurement is read as pulse.Xn.width, .period or .frequency");
    p.name = input;
    p.family = kind;
    p.field = what;
    return p;
  }
  if (registered_family(kind)) return extension_probe(text, kind, rest);
  throw Error("'" + text + "': unknown kind '" + kind + ".' (" + listed_families() + ")");
}

}  // namespace scenario
}  // namespace plc_cell
