#include "plc_cell/scenario/wall_clock.h"

#include <algorithm>

#include "plc_cell/scenario/resolution.h"
#include "plc_cell/scenario/runner.h"

namespace plc_cell {
namespace scenario {

namespace {

bool resolves(const CellConfig& config, const Probe& p, Address* a) {
  if (p.kind != Probe::Kind::Address) return false;
  try {
    *a = config.resolve(p.name);
    return true;
  } catch (const Error&) {
    return false;
  }
}

// p resolved in its cell's config (config_of); false when there is none or it does not resolve.
bool resolves_in(const ConfigOf& config_of, const Probe& p, Address* a, const CellConfig** config) {
  *config = config_of(p.cell);
  return *config && resolves(**config, p, a);
}

// As reports name p: a line's "robot.part_in (X3)", a lone cell's "part_in (X3)".
std::string qualified_label(const Probe& p, const CellConfig& config) {
  const std::string l = probe_label(p, config);
  return p.cell.empty() || l == p.text ? l : p.cell + "." + l;
}

// A duration as --tolerance takes it: "3.1ms".
std::string option_value(uint64_t us) {
  std::string s = wall_time(us);
  s.erase(std::remove(s.begin(), s.end(), ' '), s.end());
  return s;
}

bool drives_terminal(Step::Kind k) { return k == Step::Kind::Set || k == Step::Kind::Pulse || k == Step::Kind::Ramp; }

// The checks of one case, collecting into out.
class Checker {
 public:
  Checker(const WallClockRules& rules, const ConfigOf& config_of, Preflight* out)
      : rules_(rules), config_of_(config_of), out_(out) {}

  void refuse(const std::string& file, int line, const std::string& key, const std::string& why) {
    Diagnostic d;
    d.where.file = file;
    d.where.line = line;
    d.message = "key '" + key + "': " + why;
    for (const auto& e : out_->errors)
      if (e.where.line == line && e.where.file == file && e.message == d.message) return;
    out_->errors.push_back(d);
  }

  // A window [min, *max] (its width *max - min) against the resolution: refused, or its
  // latest bound moved out to make it as wide as the resolution when --tolerance allows.
  void window(const std::string& file, int line, const std::string& key, const std::string& what, uint64_t min,
              uint64_t* max) {
    if (!rules_.resolution_us || *max == UINT64_MAX) return;
    const uint64_t r = *rules_.resolution_us;
    if (*max - min >= r) return;
    const uint64_t need = r - (*max - min);
    if (need > rules_.tolerance_us) {
      refuse(file, line, key,
             what + " is tighter than the resolution " + wall_time(r) + " of " + rules_.target +
                 ": widen it in the file, or let --tolerance " + option_value(need) +
                 (rules_.tolerance_us ? " (not " + option_value(rules_.tolerance_us) + ")" : std::string()) +
                 " widen it");
      return;
    }
    *max += need;
    for (const auto& n : out_->widened)
      if (n.file == file && n.line == line && n.text.compare(0, what.size(), what) == 0) return;
    out_->widened.push_back({file, line, what + " widened by " + wall_time(need) + " to the resolution " +
                                             wall_time(r) + " (--tolerance " + option_value(rules_.tolerance_us) + ")"});
  }

  void step(Step& s) {
    switch (s.kind) {
      case Step::Kind::Simulate:
        refuse(s.file, s.line, s.key,
               "a real cell has no simulation to hand inputs back to: its PLC reads them from its terminals (a case "
               "drives an input with set, and frees it with release)");
        return;
      case Step::Kind::Release:
        if (!rules_.cannot_force.empty())
          refuse(s.file, s.line, s.key, rules_.target + " has nothing to release: " + rules_.cannot_force);
        return;
      case Step::Kind::Expect:
        if (s.has_window)
          window(s.file, s.line, s.key,
                 s.window_min_us ? "between [" + wall_time(s.window_min_us) + ", " + wall_time(s.window_max_us) + "]"
                                 : "within " + wall_time(s.window_max_us),
                 s.window_min_us, &s.window_max_us);
        return;
      case Step::Kind::WaitUntil:
        window(s.file, s.line, s.key, "timeout " + wall_time(s.timeout_us), 0, &s.timeout_us);
        return;
      case Step::Kind::Sequence:
        for (size_t i = 0; i < s.sequence.size(); ++i) {
          SequenceEntry& e = s.sequence[i];
          const std::string what = "entry " + std::to_string(i + 1) + "'s " +
                                   (e.min_us ? "between [" + wall_time(e.min_us) + ", " + wall_time(e.max_us) + "]"
                                             : "within " + wall_time(e.max_us));
          window(s.file, e.line, s.key, what, e.min_us, &e.max_us);
        }
        window(s.file, s.line, s.key, "timeout " + wall_time(s.timeout_us), 0, &s.timeout_us);
        return;
      default:
        break;
    }
    for (Assignment& a : s.assignments) assignment(s, a);
  }

  void assignment(const Step& s, Assignment& a) {
    if (a.target.kind != Probe::Kind::Address) {
      const std::string what = a.value.has_unit ? "'" + a.value.text + "' is a signal of the cell's simulated module"
                                                : "it is a stimulus of the simulated cell";
      refuse(s.file, a.line, s.key,
             a.target.text + ": " + what + ": " + rules_.target +
                 " cannot drive a sensor over its link (write the registers behind it, or drive the sensor itself)");
      return;
    }
    Address addr;
    const CellConfig* config = nullptr;
    if (!resolves_in(config_of_, a.target, &addr, &config)) return;
    const bool holds = s.kind == Step::Kind::Force || (drives_terminal(s.kind) && is_input(addr));
    if (holds && !rules_.cannot_force.empty())
      refuse(s.file, a.line, s.key,
             qualified_label(a.target, *config) + ": " + rules_.target + " cannot hold it: " + rules_.cannot_force);
    if (s.kind == Step::Kind::Pulse)
      window(s.file, a.line, s.key, "a pulse of " + wall_time(a.duration_us) + " on " + a.target.text, 0,
             &a.duration_us);
  }

  // A property's grace is how long a violation may last. The values of one poll are each the
  // PLC's at some moment within the resolution (read in several frames, or from several
  // topics), so a violation no longer than that cannot be told from their spread: every
  // property is checked with at least the resolution as its grace, and the run says so.
  void property(Property& p) {
    if (!rules_.resolution_us || p.within_us >= *rules_.resolution_us) return;
    const std::string was = p.within_us ? "its grace within " + wall_time(p.within_us) : "no grace";
    p.within_us = *rules_.resolution_us;
    out_->widened.push_back({p.file, p.line, "property " + p.text + ": " + was + ", checked with the resolution " +
                                                 wall_time(p.within_us) + " as its grace"});
  }

 private:
  const WallClockRules& rules_;
  const ConfigOf& config_of_;
  Preflight* out_;
};

std::string on_off(const Value& v) { return v.number != 0 ? "ON" : "OFF"; }

}  // namespace

bool is_input(const Address& a) { return a.area == Area::X && a.width == Width::Bit; }

Preflight wall_clock_preflight(const Case& c, const WallClockRules& rules, const CellConfig& config) {
  const ConfigOf lone = [&config](const std::string& cell) { return cell.empty() ? &config : nullptr; };
  return wall_clock_preflight(c, rules, lone);
}

Preflight wall_clock_preflight(const Case& c, const WallClockRules& rules, const ConfigOf& config_of) {
  Preflight out;
  out.adjusted = c;
  Checker check(rules, config_of, &out);
  for (Step& s : out.adjusted.steps) check.step(s);
  for (Property& p : out.adjusted.properties) check.property(p);
  std::stable_sort(out.errors.begin(), out.errors.end(),
                   [](const Diagnostic& a, const Diagnostic& b) { return a.where.line < b.where.line; });
  std::stable_sort(out.widened.begin(), out.widened.end(),
                   [](const StepNote& a, const StepNote& b) { return a.line < b.line; });
  return out;
}

std::vector<TouchedPoint> touched_points(const Case& c, const CellConfig& config) {
  return touched_points(c, config, "");
}

std::vector<TouchedPoint> touched_points(const Case& c, const CellConfig& config, const std::string& cell) {
  std::vector<TouchedPoint> out;
  for (const Step& s : c.steps) {
    if (s.kind == Step::Kind::Simulate) continue;
    for (const Assignment& a : s.assignments) {
      Address addr;
      if (a.target.cell != cell || !resolves(config, a.target, &addr)) continue;
      const bool held = s.kind == Step::Kind::Force || (drives_terminal(s.kind) && is_input(addr));
      auto it = std::find_if(out.begin(), out.end(), [&](const TouchedPoint& t) { return t.address == addr; });
      if (it == out.end()) it = out.insert(out.end(), {addr, qualified_label(a.target, config), false});
      it->held = it->held || held;
    }
  }
  return out;
}

std::vector<StepNote> planned_actions(const Case& c, const CellConfig& config) {
  std::vector<StepNote> out;
  for (const Step& s : c.steps) {
    if (s.kind == Step::Kind::Release && s.assignments.empty())
      out.push_back({s.file, s.line, "release every point this case forced"});
    for (const Assignment& a : s.assignments) {
      Address addr;
      if (!resolves(config, a.target, &addr)) continue;
      const std::string label = probe_label(a.target, config);
      const bool input = is_input(addr);
      std::string text;
      switch (s.kind) {
        case Step::Kind::Set:
          text = input ? "force " + label + " " + on_off(a.value) + " (held as its terminal)"
                       : "write " + label + " = " + a.value.text;
          break;
        case Step::Kind::Write:
          text = "write " + label + " = " + a.value.text;
          break;
        case Step::Kind::Force:
          text = "force " + label + " " + on_off(a.value);
          break;
        case Step::Kind::Release:
          text = "release " + label;
          break;
        case Step::Kind::Pulse:
          text = (input ? "force " + label + " ON, then OFF after " : "write " + label + " = 1, then 0 after ") +
                 wall_time(a.duration_us);
          break;
        case Step::Kind::Ramp:
          text = (input ? "force " : "write ") + label + " from " + a.from.text + " to " + a.value.text + " over " +
                 wall_time(a.duration_us) + ", at every poll";
          break;
        default:
          continue;
      }
      out.push_back({s.file, a.line, text});
    }
  }
  return out;
}

}  // namespace scenario
}  // namespace plc_cell
