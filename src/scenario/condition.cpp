#include "plc_cell/scenario/condition.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace scenario {

namespace {

std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> w;
  for (std::string s; in >> s;) w.push_back(s);
  return w;
}

bool parse_op(const std::string& s, Comparison::Op* op) {
  static const std::pair<const char*, Comparison::Op> ops[] = {
      {"==", Comparison::Op::Eq}, {"!=", Comparison::Op::Ne}, {"<", Comparison::Op::Lt},
      {"<=", Comparison::Op::Le}, {">", Comparison::Op::Gt}, {">=", Comparison::Op::Ge}};
  for (const auto& o : ops)
    if (s == o.first) {
      *op = o.second;
      return true;
    }
  return false;
}

bool parse_number(const std::string& s, double* v) {
  if (s == "on" || s == "ON" || s == "true") return *v = 1, true;
  if (s == "off" || s == "OFF" || s == "false") return *v = 0, true;
  if (s.empty()) return false;
  char* end = nullptr;
  // Integers in any base strtoll knows (0x10), else decimals.
  const long long i = std::strtoll(s.c_str(), &end, 0);
  if (*end == '\0') return *v = double(i), true;
  const double d = std::strtod(s.c_str(), &end);
  if (*end == '\0' && std::isfinite(d)) return *v = d, true;
  return false;
}

// A sum of names and numbers on both sides of one operator: TERM (+|- TERM)* OP TERM
// (+|- TERM)* [+- TOL], the first term a name. The names go to c.probe and c.more (the
// right side's with their sign turned), the numbers to c.value (the left side's turned).
Comparison sum(const std::vector<std::string>& w, const std::string& text, Naming naming) {
  Comparison c;
  c.text = text;
  size_t end = w.size();
  if (end >= 2 && (w[end - 2] == "+-" || w[end - 2] == "±")) {
    if (!parse_number(w[end - 1], &c.tolerance) || c.tolerance < 0) throw Error("'" + text + "': +- takes a number >= 0");
    end -= 2;
  }
  size_t op_at = 0;
  while (op_at < end && !parse_op(w[op_at], &c.op)) ++op_at;
  if (op_at == end) throw Error("'" + text + "': a sum is compared: A + B == C (==, !=, <, <=, > or >=)");
  if (c.tolerance > 0 && c.op != Comparison::Op::Eq && c.op != Comparison::Op::Ne)
    throw Error("'" + text + "': a tolerance (+-) goes with == or != only");
  bool first = true;
  for (int side : {1, -1}) {
    const size_t from = side == 1 ? 0 : op_at + 1, to = side == 1 ? op_at : end;
    int sign = 1;
    for (size_t i = from; i < to; ++i) {
      const bool term = (i - from) % 2 == 0;
      if (!term) {
        if (w[i] != "+" && w[i] != "-") throw Error("'" + text + "': expected + or - between terms, got '" + w[i] + "'");
        sign = w[i] == "+" ? 1 : -1;
        continue;
      }
      if (w[i] == "+" || w[i] == "-") throw Error("'" + text + "': a term is missing before '" + w[i] + "'");
      double v;
      if (parse_number(w[i], &v)) {
        c.value -= side * sign * v;
      } else if (first) {
        if (sign != 1) throw Error("'" + text + "': a sum starts with a name (A + B == C)");
        c.probe = parse_probe(w[i], naming);
      } else {
        c.more.push_back({side * sign, parse_probe(w[i], naming)});
      }
      if (!parse_number(w[i], &v)) first = false;
    }
    if (to == from || (to - from) % 2 == 0) throw Error("'" + text + "': a term is missing at the end of a side");
    if (first) throw Error("'" + text + "': a sum starts with a name (A + B == C)");
  }
  for (const Probe* p : c.probes())
    if (p->kind == Probe::Kind::AxisState) throw Error("'" + text + "': an axis state is a word: it is not summed");
  return c;
}

// One comparison from its words: NAME | not NAME | NAME OP VALUE [C] [+- TOL], or a sum.
Comparison comparison(const std::vector<std::string>& w, const std::string& text, Naming naming) {
  if (std::find_if(w.begin(), w.end(), [](const std::string& x) { return x == "+" || x == "-"; }) != w.end())
    return sum(w, text, naming);
  Comparison c;
  c.text = text;
  size_t i = 0;
  bool negated = false;
  if (w[0] == "not" || w[0] == "!") {
    negated = true;
    ++i;
  } else if (w[0].size() > 1 && w[0][0] == '!') {
    negated = true;
  }
  if (i >= w.size()) throw Error("'" + text + "': 'not' of what?");
  c.probe = parse_probe(negated && i == 0 ? w[0].substr(1) : w[i], naming);
  ++i;
  // The units the probe's family reads in (config/probe_facet.h), the longest first.
  std::vector<std::string> units;
  if (c.probe.kind != Probe::Kind::Address)
    if (const auto f = registered_probe_family(c.probe.family)) units = f->reading_units;
  std::sort(units.begin(), units.end(), [](const std::string& a, const std::string& b) { return a.size() > b.size(); });
  const auto is_unit = [&](const std::string& x) { return std::find(units.begin(), units.end(), x) != units.end(); };
  if (i == w.size()) {
    if (c.probe.kind == Probe::Kind::AxisState)
      throw Error("'" + text + "': an axis state is compared with a word (== idle, moving or error)");
    c.op = negated ? Comparison::Op::Eq : Comparison::Op::Ne;  // "Y0": not 0; "not Y0": 0
    c.value = 0;
    return c;
  }
  if (negated) throw Error("'" + text + "': 'not' takes a name alone (not Y0), not a comparison");
  if (!parse_op(w[i], &c.op))
    throw Error("'" + text + "': expected ==, !=, <, <=, > or >= after " + c.probe.text + ", got '" + w[i] + "'");
  if (++i == w.size()) throw Error("'" + text + "': no value after " + w[i - 1]);
  const std::string& v = w[i];
  if (c.probe.kind == Probe::Kind::AxisState) {
    if (v != "idle" && v != "moving" && v != "error")
      throw Error("'" + text + "': an axis state is idle, moving or error, not '" + v + "'");
    if (c.op != Comparison::Op::Eq && c.op != Comparison::Op::Ne)
      throw Error("'" + text + "': an axis state compares with == or != only");
    c.word = v;
    ++i;
  } else {
    std::string num = v;
    // A reading may carry its family's unit: "200 C", "200C", "200 degC" for a temperature.
    for (const std::string& u : units) {
      if (num.size() > u.size() && num.compare(num.size() - u.size(), u.size(), u) == 0) {
        num.resize(num.size() - u.size());
        break;
      }
    }
    if (!parse_number(num, &c.value)) throw Error("'" + text + "': '" + v + "' is not a number");
    ++i;
    if (i < w.size() && is_unit(w[i])) ++i;
  }
  if (i < w.size() && (w[i] == "+-" || w[i] == "±")) {
    if (c.op != Comparison::Op::Eq && c.op != Comparison::Op::Ne)
      throw Error("'" + text + "': a tolerance (+-) goes with == or != only");
    if (++i == w.size() || !parse_number(w[i], &c.tolerance) || c.tolerance < 0)
      throw Error("'" + text + "': +- takes a number >= 0");
    ++i;
    if (i < w.size() && is_unit(w[i])) ++i;
  }
  if (i < w.size()) throw Error("'" + text + "': unexpected '" + w[i] + "' (join comparisons with 'and')");
  return c;
}

}  // namespace

bool Comparison::holds(const Reading& r) const {
  if (!word.empty()) return (r.word == word) == (op == Op::Eq);
  if (!r.valid) return op == Op::Ne;  // NaN: equal to nothing, ordered with nothing
  const double x = r.number;
  switch (op) {
    case Op::Eq: return std::fabs(x - value) <= tolerance;
    case Op::Ne: return std::fabs(x - value) > tolerance;
    case Op::Lt: return x < value;
    case Op::Le: return x <= value;
    case Op::Gt: return x > value;
    case Op::Ge: return x >= value;
  }
  return false;
}

bool Comparison::holds(const std::function<Reading(const Probe&)>& read) const {
  if (more.empty()) return holds(read(probe));
  Reading total = read(probe);
  for (const Term& t : more) {
    const Reading r = read(t.probe);
    total.valid = total.valid && r.valid;
    total.number += t.sign * r.number;
  }
  return holds(total);
}

std::vector<const Probe*> Comparison::probes() const {
  std::vector<const Probe*> out{&probe};
  for (const Term& t : more) out.push_back(&t.probe);
  return out;
}

Condition parse_condition(const std::string& text, Naming naming) {
  Condition cond;
  cond.text = text;
  const auto w = words(text);
  if (w.empty()) throw Error("empty condition");
  std::vector<std::string> part;
  std::string part_text;
  auto flush = [&] {
    if (part.empty()) throw Error("'" + text + "': 'and' needs a comparison on each side");
    cond.all.push_back(comparison(part, part_text, naming));
    part.clear();
    part_text.clear();
  };
  for (const auto& s : w) {
    if (s == "and") {
      flush();
      continue;
    }
    if (s == "or") throw Error("'" + text + "': 'or' is not supported (a condition is comparisons joined by 'and')");
    part.push_back(s);
    part_text += (part_text.empty() ? "" : " ") + s;
  }
  flush();
  return cond;
}

void apply_tolerance(Condition& c, double tolerance) {
  for (auto& cmp : c.all)
    if (cmp.tolerance == 0 && cmp.word.empty()) cmp.tolerance = tolerance;
}

}  // namespace scenario
}  // namespace plc_cell
