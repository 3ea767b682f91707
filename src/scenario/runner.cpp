#include "plc_cell/scenario/runner.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "plc_cell/core/error.h"
#include "plc_cell/scenario/property.h"

namespace plc_cell {
namespace scenario {

std::string format_time(uint64_t us) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%" PRIu64 ".%03u s", us / 1000000, unsigned(us % 1000000 / 1000));
  std::string s = buf;
  if (us % 1000) {  // below a millisecond: the microseconds too
    std::snprintf(buf, sizeof buf, "%" PRIu64 ".%06u s", us / 1000000, unsigned(us % 1000000));
    s = buf;
  }
  return s;
}

namespace {

struct Failure {
  std::string what;     // the expectation and why it failed
  uint64_t at_us;
  std::vector<const Condition*> involved;
  std::string where;    // "file:line: " of a property; empty: the step's
};

// One case in progress: the timeline, what runs in the background (pulses, ramps), and
// every probe's recent changes for the failure report.
class CaseRun {
 public:
  CaseRun(const Case& c, Target& t) : case_(c), t_(t), period_(t.period_us()) {
    for (const auto& s : c.steps) {
      add_probes(s.cond);
      for (const auto& e : s.sequence) add_probes(e.cond);
      for (const auto& a : s.assignments) add_probe(a.target);
    }
    for (const auto& p : c.properties) {
      add_probes(p.when);
      add_probes(p.cond);
      watches_.emplace_back(p);
    }
  }

  CaseResult run() {
    CaseResult r;
    r.name = case_.name;
    r.file = case_.file;
    r.line = case_.line;
    record();
    for (const auto& s : case_.steps) {
      try {
        step(s);
      } catch (const Failure& f) {
        r.failure = (f.where.empty() ? where(s) : f.where) + f.what;
        r.details = details(f);
        r.virtual_us = f.at_us;
        r.scans = scans_;
        return r;
      } catch (const Error& e) {
        r.failure = where(s) + s.key + ": " + e.what();
        r.details = "  at " + format_time(now_) + "\n";
        r.virtual_us = now_;
        r.scans = scans_;
        return r;
      }
    }
    r.passed = true;
    r.virtual_us = now_;
    r.scans = scans_;
    return r;
  }

 private:
  struct Background {
    Assignment a;
    Step::Kind kind;
    uint64_t start_us;
  };
  struct Change {
    uint64_t t_us;
    std::string text;
    bool initial;  // before the first scan
  };

  static std::string where(const Step& s) { return s.file + ":" + std::to_string(s.line) + ": "; }

  void add_probe(const Probe& p) {
    if (known_.insert(p.text).second) probes_.push_back(p);
  }
  void add_probes(const Condition& c) {
    for (const auto& cmp : c.all)
      for (const Probe* p : cmp.probes()) add_probe(*p);
  }

  // The probes' values after a scan (or at the start): a change is kept with its time.
  void record() {
    for (const auto& p : probes_) {
      if (p.kind == Probe::Kind::Analog) continue;  // a stimulus: what the steps set
      const Reading r = t_.read(p);
      auto& h = history_[p.text];
      if (h.empty() || h.back().text != r.text) {
        h.push_back({now_, r.text, scans_ == 0});
        if (h.size() > kHistoryDepth) h.pop_front();
      }
    }
  }

  // Pulses end and ramps move before the scan at t.
  void background(uint64_t t) {
    for (auto it = background_.begin(); it != background_.end();) {
      const Assignment& a = it->a;
      const uint64_t elapsed = t - it->start_us;
      if (it->kind == Step::Kind::Pulse) {
        if (elapsed >= a.duration_us) {
          Value off;
          off.number = 0;
          off.text = "off";
          drive(a.target, off);
          it = background_.erase(it);
          continue;
        }
      } else {
        const double f = a.duration_us == 0 || elapsed >= a.duration_us ? 1.0 : double(elapsed) / double(a.duration_us);
        Value v = a.value;
        v.number = a.from.number + (a.value.number - a.from.number) * f;
        if (!v.has_unit) v.number = double(llround(v.number));  // a register holds whole counts
        drive(a.target, v);
        if (f >= 1.0) {
          it = background_.erase(it);
          continue;
        }
      }
      ++it;
    }
  }

  void drive(const Probe& p, const Value& v) { t_.set(p, v); }

  void scan_next() {
    const uint64_t t = next_scan_;
    background(t);
    t_.scan(t);
    ++scans_;
    now_ = std::max(t, t_.scanned_at(t));
    // A wall-clock target whose poll came late goes on from where it is, not with a burst.
    next_scan_ += period_;
    while (next_scan_ <= now_) next_scan_ += period_;
    record();
    const std::string fault = t_.fault();
    if (!fault.empty()) throw Failure{"the PLC stopped on a fault: " + fault, now_, {}, {}};
    check_properties();
  }

  // Every property after every scan; a violation longer than its grace fails the case.
  void check_properties() {
    const uint64_t spread = watches_.empty() ? 0 : t_.spread_us();
    for (auto& w : watches_) {
      const Property& p = w.property();
      const bool violated = p.violated([&](const Condition& c) { return holds(c); });
      if (!w.failed(violated, now_, spread)) continue;
      std::string what = "property " + p.text + " violated";
      const uint64_t grace = std::max(p.within_us, spread);
      if (grace)
        what += " for longer than " + format_time(grace) +
                (grace > p.within_us ? ", the spread of the values read so far in the run," : "") + " (since " +
                format_time(w.since_us()) + ")";
      what += ": " + actual(p.when.empty() ? p.cond : p.when);
      if (!p.when.empty()) what += "; " + actual(p.cond);
      std::vector<const Condition*> involved{&p.cond};
      if (!p.when.empty()) involved.insert(involved.begin(), &p.when);
      throw Failure{what, now_, involved, p.file + ":" + std::to_string(p.line) + ": "};
    }
  }

  void advance_to(uint64_t t) {
    while (next_scan_ <= t) scan_next();
    if (t > now_) now_ = t;
  }

  void cancel_background(const Probe& p) {
    for (auto it = background_.begin(); it != background_.end();)
      it = it->a.target == p ? background_.erase(it) : it + 1;
  }

  // "R0 is 3, Y0 is ON": every comparison of c as it reads now.
  std::string actual(const Condition& c) {
    std::string s;
    std::set<std::string> seen;
    for (const auto& cmp : c.all)
      for (const Probe* p : cmp.probes()) {
        if (!seen.insert(p->text).second) continue;
        s += (s.empty() ? "" : ", ") + label(*p) + " is " + t_.read(*p).text;
      }
    return s;
  }
  // What is still false of c, with the values: "motor (Y0) is OFF" for a bare name (the
  // comparison says no more), else "R0 >= 3 (R0 is 1)".
  std::string still_false(const Condition& c) {
    std::string s;
    for (const auto& cmp : c.all) {
      if (cmp.holds(reader())) continue;
      std::string value;
      for (const Probe* p : cmp.probes()) value += (value.empty() ? "" : ", ") + label(*p) + " is " + t_.read(*p).text;
      s += (s.empty() ? "" : "; ") + (cmp.text == cmp.probe.text ? value : cmp.text + " (" + value + ")");
    }
    return s;
  }
  // The name reports use, once per probe: "stop_pb (X1)".
  const std::string& label(const Probe& p) {
    auto it = labels_.find(p.text);
    if (it == labels_.end()) it = labels_.emplace(p.text, t_.label(p)).first;
    return it->second;
  }
  std::function<Reading(const Probe&)> reader() {
    return [this](const Probe& p) { return t_.read(p); };
  }
  bool holds(const Condition& c) {
    for (const auto& cmp : c.all)
      if (cmp.more.empty() ? !cmp.holds(t_.read(cmp.probe)) : !cmp.holds(reader())) return false;
    return true;
  }

  [[noreturn]] void fail(const std::string& what, std::vector<const Condition*> involved) {
    throw Failure{what, now_, std::move(involved), {}};
  }

  std::string details(const Failure& f) {
    std::ostringstream o;
    o << "  at " << format_time(f.at_us) << "\n";
    std::vector<const Probe*> shown;
    for (const Condition* c : f.involved)
      for (const auto& cmp : c->all)
        for (const Probe* q : cmp.probes())
          if (std::find_if(shown.begin(), shown.end(), [&](const Probe* p) { return *p == *q; }) == shown.end())
            shown.push_back(q);
    if (!shown.empty()) o << "  last changes (time value):\n";
    for (const Probe* p : shown) {
      o << "    " << label(*p) << ":";
      for (const auto& ch : history_[p->text])
        o << "  " << (ch.initial ? std::string("initially") : format_time(ch.t_us)) << " " << ch.text;
      o << "\n";
    }
    return o.str();
  }

  void step(const Step& s) {
    if (s.has_at) {
      if (s.at_us < now_)
        fail("at " + format_time(s.at_us) + " is before now (" + format_time(now_) + ")", {});
      advance_to(s.at_us);
    }
    if (s.after_us) advance_to(now_ + s.after_us);
    switch (s.kind) {
      case Step::Kind::Wait:
        return;
      case Step::Kind::Set:
        for (const auto& a : s.assignments) {
          cancel_background(a.target);
          t_.set(a.target, a.value);
        }
        return;
      case Step::Kind::Write:
        for (const auto& a : s.assignments) t_.write(a.target, a.value);
        return;
      case Step::Kind::Force:
        for (const auto& a : s.assignments) t_.force(a.target, a.value.number != 0);
        return;
      case Step::Kind::Release:
        if (s.assignments.empty()) t_.release(nullptr);
        for (const auto& a : s.assignments) t_.release(&a.target);
        return;
      case Step::Kind::Simulate:
        if (s.assignments.empty()) {
          // A pulse still running would take its input again when it ends.
          background_.erase(std::remove_if(background_.begin(), background_.end(),
                                           [](const Background& b) { return b.kind == Step::Kind::Pulse; }),
                            background_.end());
          t_.simulate(nullptr);
        }
        for (const auto& a : s.assignments) {
          cancel_background(a.target);
          t_.simulate(&a.target);
        }
        return;
      case Step::Kind::Pulse:
      case Step::Kind::Ramp:
        for (const auto& a : s.assignments) {
          cancel_background(a.target);
          if (s.kind == Step::Kind::Pulse) t_.set(a.target, a.value);
          background_.push_back({a, s.kind, next_scan_});
          if (s.kind == Step::Kind::Ramp) background(next_scan_);  // the start value before the next scan
        }
        return;
      case Step::Kind::Expect:
        return expect(s);
      case Step::Kind::WaitUntil:
        return wait_until(s);
      case Step::Kind::Sequence:
        return sequence(s);
    }
  }

  void expect(const Step& s) {
    const std::string what = "expect " + s.cond.text;
    const uint64_t t0 = now_;
    if (s.stays_us) {
      const std::string w = what + " to stay for " + format_time(s.stays_us);
      if (!holds(s.cond)) fail(w + ": false at its start: " + still_false(s.cond), {&s.cond});
      while (next_scan_ <= t0 + s.stays_us) {
        scan_next();
        if (!holds(s.cond))
          fail(w + ": false at " + format_time(now_) + " (" + format_time(now_ - t0) + " in): " + still_false(s.cond),
               {&s.cond});
      }
      advance_to(t0 + s.stays_us);
      return;
    }
    if (s.has_window) {
      const std::string w = what + (s.window_min_us ? " between " + format_time(s.window_min_us) + " and " +
                                                          format_time(s.window_max_us)
                                                    : " within " + format_time(s.window_max_us));
      for (;;) {
        if (holds(s.cond)) {
          if (now_ - t0 < s.window_min_us)
            fail(w + ": held already at " + format_time(now_) + " (" + format_time(now_ - t0) +
                     " in, before the window): " + actual(s.cond),
                 {&s.cond});
          if (now_ - t0 > s.window_max_us)  // seen only by a scan that came late
            fail(w + ": held only at " + format_time(now_) + " (" + format_time(now_ - t0) +
                     " in, after the window): " + actual(s.cond),
                 {&s.cond});
          return;
        }
        if (next_scan_ > t0 + s.window_max_us) break;
        scan_next();
      }
      advance_to(t0 + s.window_max_us);
      fail(w + ": never held: " + still_false(s.cond), {&s.cond});
    }
    if (!holds(s.cond)) fail(what + ": " + still_false(s.cond), {&s.cond});
  }

  void wait_until(const Step& s) {
    const uint64_t t0 = now_;
    while (!holds(s.cond)) {
      if (next_scan_ > t0 + s.timeout_us) {
        advance_to(t0 + s.timeout_us);
        fail("wait_until " + s.cond.text + ": still false after " + format_time(s.timeout_us) + ": " +
                 still_false(s.cond),
             {&s.cond});
      }
      scan_next();
    }
  }

  void sequence(const Step& s) {
    const uint64_t t0 = now_;
    const size_t n = s.sequence.size();
    std::vector<bool> before(n);
    for (size_t i = 0; i < n; ++i) before[i] = holds(s.sequence[i].cond);
    // When each entry last turned true; none: true since the start or never true.
    std::vector<std::optional<uint64_t>> rose(n);
    size_t next = 0;
    uint64_t last_match = t0;
    std::vector<const Condition*> involved;
    for (const auto& e : s.sequence) involved.push_back(&e.cond);
    auto label = [&](size_t i) {
      return "entry " + std::to_string(i + 1) + " (line " + std::to_string(s.sequence[i].line) + ") '" +
             s.sequence[i].cond.text + "'";
    };
    auto since = [&](size_t i) {
      return i == 0 ? std::string("the start of the sequence") : "entry " + std::to_string(i) + "'s match";
    };
    // Why entry i has not matched: what is still false, or, when it holds, that it holds
    // without having changed where it could count (an entry is a change).
    auto why = [&](size_t i) {
      const Condition& c = s.sequence[i].cond;
      if (!holds(c)) return still_false(c);
      const std::string before_match = i == 0 ? "" : ", before " + since(i) + " at " + format_time(last_match);
      if (!rose[i])
        return "already true when the sequence started" + before_match + ", and never went false since: " + actual(c);
      return "became true at " + format_time(*rose[i]) + before_match + ", and never went false since: " + actual(c);
    };
    while (next < n) {
      if (next_scan_ > t0 + s.timeout_us) {
        advance_to(t0 + s.timeout_us);
        fail("expect_sequence: " + label(next) + " did not happen within the sequence's " +
                 format_time(s.timeout_us) + ": " + why(next),
             involved);
      }
      const SequenceEntry& e = s.sequence[next];
      if (e.max_us != UINT64_MAX && next_scan_ > last_match + e.max_us) {
        advance_to(last_match + e.max_us);
        fail("expect_sequence: " + label(next) + " did not happen within " + format_time(e.max_us) + " of " +
                 since(next) + " at " + format_time(last_match) + ": " + why(next),
             involved);
      }
      scan_next();
      std::vector<bool> now(n);
      for (size_t i = 0; i < n; ++i) {
        now[i] = holds(s.sequence[i].cond);
        if (now[i] && !before[i]) rose[i] = now_;
      }
      // Entries match in order; several may change at the same scan.
      while (next < n && now[next] && !before[next]) {
        const SequenceEntry& m = s.sequence[next];
        if (now_ - last_match < m.min_us)
          fail("expect_sequence: " + label(next) + " happened " + format_time(now_ - last_match) + " after " +
                   since(next) + ", before the earliest " + format_time(m.min_us) + ": " + actual(m.cond),
               involved);
        if (m.max_us != UINT64_MAX && now_ - last_match > m.max_us)  // seen only by a scan that came late
          fail("expect_sequence: " + label(next) + " happened " + format_time(now_ - last_match) + " after " +
                   since(next) + ", after the latest " + format_time(m.max_us) + ": " + actual(m.cond),
               involved);
        last_match = now_;
        ++next;
      }
      before = now;
    }
  }

  const Case& case_;
  Target& t_;
  const uint64_t period_;
  uint64_t now_ = 0;
  uint64_t next_scan_ = 0;
  uint64_t scans_ = 0;
  std::vector<Probe> probes_;
  std::set<std::string> known_;
  std::map<std::string, std::deque<Change>> history_;
  std::map<std::string, std::string> labels_;  // by probe text
  std::vector<Background> background_;
  std::vector<PropertyWatch> watches_;
};

}  // namespace

CaseResult run_case(const Case& c, Target& target) { return CaseRun(c, target).run(); }

std::vector<Diagnostic> check_case(const Case& c, Target& target) {
  std::vector<Diagnostic> errors;
  auto check = [&](const Step& s, int line, const Probe& p, bool writing) {
    const std::string why = target.check(p, writing);
    if (why.empty()) return;
    Diagnostic d;
    d.where.file = s.file;
    d.where.line = line ? line : s.line;
    d.message = "key '" + s.key + "': " + why;
    for (const auto& o : errors)
      if (o.where.line == d.where.line && o.message == d.message) return;
    errors.push_back(d);
  };
  for (const auto& s : c.steps) {
    for (const auto& a : s.assignments) check(s, a.line, a.target, s.kind != Step::Kind::Release && s.kind != Step::Kind::Simulate);
    for (const auto& cmp : s.cond.all)
      for (const Probe* p : cmp.probes()) check(s, s.line, *p, false);
    for (const auto& e : s.sequence)
      for (const auto& cmp : e.cond.all)
        for (const Probe* p : cmp.probes()) check(s, e.line, *p, false);
  }
  for (const auto& p : c.properties) {
    Step at;  // the property's line, under its key
    at.file = p.file;
    at.key = p.never ? "never" : "always";
    at.line = p.line;
    for (const Condition* cond : {&p.when, &p.cond})
      for (const auto& cmp : cond->all)
        for (const Probe* q : cmp.probes()) check(at, p.line, *q, false);
  }
  return errors;
}

}  // namespace scenario
}  // namespace plc_cell
