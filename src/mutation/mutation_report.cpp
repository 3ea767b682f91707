#include "plc_cell/mutation/mutation_report.h"

#include <cstdio>

namespace plc_cell {
namespace mutation {

namespace {

std::string percent(double v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%.1f %%", v * 100);
  return buf;
}

std::string json_string(const std::string& s) {
  std::string o = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') o += '\\', o += char(c);
    else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      o += buf;
    } else o += char(c);
  }
  return o + "\"";
}

std::string html(const std::string& s) {
  std::string o;
  for (char c : s) o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return o;
}

const std::vector<std::string>& executed(const ProgramResult& p, int line) {
  static const std::vector<std::string> none;
  const auto it = p.executed_by.find(line);
  return it == p.executed_by.end() ? none : it->second;
}

// "every case", "a; b"
std::string cases_text(const ProgramResult& p, const std::vector<std::string>& by) {
  if (by.size() == p.cases) return "every case";
  std::string s;
  for (size_t i = 0; i < by.size(); ++i) s += (i ? "; " : "") + by[i];
  return s;
}

// "survived, not observed: ..." with what tells it apart.
std::string why(const ProgramResult& p, const MutantResult& r) {
  if (r.verdict == Verdict::Equivalent)
    return "equivalent-suspect: no case and no input search tells it apart (" + r.searched + ")";
  const auto& by = executed(p, r.mutant.line);
  const std::string found = r.told_apart.empty() ? "" : "; an input search tells it apart: " + r.told_apart;
  switch (survival(p, r)) {
    case Survival::NotExecuted: return "survived: no case executes it" + found;
    case Survival::NotObserved:
      return "survived: executed (by " + cases_text(p, by) + "), but no case sees a difference" + found;
    case Survival::NotChecked: break;
  }
  return by.size() == p.cases ? "survived: no case checks it (executed by every case)"
                              : "survived: no case checks it (executed by: " + cases_text(p, by) + ")";
}

void count(const ProgramResult& p, const MutantResult& r, Score& s) {
  switch (r.verdict) {
    case Verdict::Killed: ++s.killed; return;
    case Verdict::Equivalent: ++s.equivalent; return;
    case Verdict::NotLoaded: ++s.not_loaded; return;
    case Verdict::Survived: break;
  }
  ++s.survived;
  const Survival v = survival(p, r);
  ++(v == Survival::NotExecuted ? s.not_executed : v == Survival::NotObserved ? s.not_observed : s.not_checked);
}

std::vector<Score> per_network(const ProgramResult& p) {
  std::vector<Score> s(p.networks.size() + 1);
  for (const auto& r : p.results) {
    const NetworkSpan* n = network_of(p, r.mutant.line);
    count(p, r, s[n ? n->number : 0]);
  }
  return s;
}

// "network 5 (line 31)"
std::string network_text(const NetworkSpan& n) {
  return "network " + std::to_string(n.number) + " (line " + std::to_string(n.line) + ")";
}

std::string where(const ProgramResult& p, const MutantResult& r) {
  const NetworkSpan* n = network_of(p, r.mutant.line);
  return n ? " in " + network_text(*n) : "";
}

}  // namespace

const char* survival_name(Survival s) {
  switch (s) {
    case Survival::NotExecuted: return "not executed";
    case Survival::NotObserved: return "not observed";
    case Survival::NotChecked: return "not checked";
  }
  return "?";
}

Survival survival(const ProgramResult& p, const MutantResult& r) {
  if (executed(p, r.mutant.line).empty()) return Survival::NotExecuted;
  return r.observed ? Survival::NotChecked : Survival::NotObserved;
}

Score score(const ProgramResult& p) {
  Score s;
  for (const auto& r : p.results) count(p, r, s);
  return s;
}

const NetworkSpan* network_of(const ProgramResult& p, int line) {
  for (const auto& n : p.networks)
    if (line >= n.line && line <= n.end_line) return &n;
  return nullptr;
}

namespace {

// "killed 5, survived 10 (not executed 0, not observed 6, not checked 4), equivalent-suspect 5,
// not loaded 0: score 33.3 %"
std::string summary(const Score& s) {
  return "killed " + std::to_string(s.killed) + ", survived " + std::to_string(s.survived) + " (not executed " +
         std::to_string(s.not_executed) + ", not observed " + std::to_string(s.not_observed) + ", not checked " +
         std::to_string(s.not_checked) + "), equivalent-suspect " + std::to_string(s.equivalent) + ", not loaded " +
         std::to_string(s.not_loaded) + (s.has_score() ? ": score " + percent(s.score()) : ": no score (no mutant counts)");
}

std::string json_or_null(const std::string& s) { return s.empty() ? "null" : json_string(s); }

}  // namespace

void write_text(const std::vector<ProgramResult>& programs, std::ostream& out) {
  for (const auto& p : programs) {
    out << "mutation testing of " << p.program << ": " << p.results.size() << " mutants";
    if (p.results.size() < p.generated) out << " (of " << p.generated << ")";
    out << ", " << p.cases << (p.cases == 1 ? " case" : " cases") << " each\n  " << summary(score(p)) << "\n";
    const auto nets = per_network(p);
    for (const auto& n : p.networks) {
      const Score& ns = nets[n.number];
      if (ns.killed + ns.survived + ns.equivalent == 0) continue;
      out << "  " << network_text(n) << ": " << ns.killed << "/" << ns.killed + ns.survived << " killed"
          << (ns.equivalent ? ", " + std::to_string(ns.equivalent) + " equivalent-suspect" : "") << "\n";
    }
    for (const auto& r : p.results)
      if (r.verdict == Verdict::Survived || r.verdict == Verdict::Equivalent)
        out << p.program << ":" << r.mutant.line << ": " << r.mutant.change() << where(p, r) << ": " << why(p, r)
            << "\n";
  }
}

void write_json(const std::vector<ProgramResult>& programs, std::ostream& out) {
  out << "{\"programs\": [";
  for (size_t i = 0; i < programs.size(); ++i) {
    const ProgramResult& p = programs[i];
    const Score s = score(p);
    out << (i ? ", " : "") << "\n  {\"file\": " << json_string(p.program) << ", \"cases\": " << p.cases
        << ", \"generated\": " << p.generated << ", \"mutants\": " << p.results.size() << ", \"killed\": " << s.killed
        << ", \"survived\": " << s.survived << ", \"survived_not_executed\": " << s.not_executed
        << ", \"survived_not_observed\": " << s.not_observed << ", \"survived_not_checked\": " << s.not_checked
        << ", \"equivalent_suspect\": " << s.equivalent << ", \"not_loaded\": " << s.not_loaded
        << ", \"score\": ";
    if (s.has_score()) out << s.score();
    else out << "null";
    out << ",\n   \"networks\": [";
    const auto nets = per_network(p);
    for (size_t k = 0; k < p.networks.size(); ++k) {
      const Score& ns = nets[p.networks[k].number];
      out << (k ? ", " : "") << "{\"number\": " << p.networks[k].number << ", \"line\": " << p.networks[k].line
          << ", \"killed\": " << ns.killed << ", \"survived\": " << ns.survived
          << ", \"equivalent_suspect\": " << ns.equivalent << "}";
    }
    out << "],\n   \"results\": [";
    for (size_t k = 0; k < p.results.size(); ++k) {
      const MutantResult& r = p.results[k];
      const NetworkSpan* n = network_of(p, r.mutant.line);
      out << (k ? "," : "") << "\n    {\"line\": " << r.mutant.line << ", \"network\": " << (n ? n->number : 0)
          << ", \"network_line\": " << (n ? std::to_string(n->line) : "null")
          << ", \"operator\": " << json_string(r.mutant.op) << ", \"from\": " << json_string(r.mutant.before)
          << ", \"to\": " << json_string(r.mutant.after) << ", \"status\": " << json_string(verdict_name(r.verdict))
          << ", \"survival\": "
          << (r.verdict == Verdict::Survived ? json_string(survival_name(survival(p, r))) : std::string("null"))
          << ", \"killed_by\": " << json_or_null(r.killed_by) << ", \"told_apart\": " << json_or_null(r.told_apart)
          << ", \"searched\": " << json_or_null(r.searched) << ", \"executed_by\": [";
      const auto& by = executed(p, r.mutant.line);
      for (size_t j = 0; j < by.size(); ++j) out << (j ? ", " : "") << json_string(by[j]);
      out << "]}";
    }
    out << "]}";
  }
  out << "\n]}\n";
}

std::string html_section(const std::vector<ProgramResult>& programs) {
  std::string o = "<section class=\"mutation\">\n<h2>Mutation testing</h2>\n";
  for (const auto& p : programs) {
    o += "<h3>" + html(p.program) + "</h3>\n<p>" + std::to_string(p.results.size()) + " mutants, " +
         html(summary(score(p))) + "</p>\n<table class=\"summary\">\n<tr><th>line</th><th>network</th>"
         "<th>mutant</th><th>status</th></tr>\n";
    for (const auto& r : p.results) {
      const bool bad = r.verdict == Verdict::Survived || r.verdict == Verdict::Equivalent;
      const NetworkSpan* n = network_of(p, r.mutant.line);
      o += "<tr class=\"" + std::string(bad ? "bad" : "ok") + "\"><td>" + std::to_string(r.mutant.line) + "</td><td>" +
           (n ? std::to_string(n->number) + " (line " + std::to_string(n->line) + ")" : "") + "</td><td>" +
           html(r.mutant.change()) + "</td><td>" +
           html(bad ? why(p, r) : std::string(verdict_name(r.verdict)) +
                                     (r.killed_by.empty() ? "" : " by " + r.killed_by)) + "</td></tr>\n";
    }
    o += "</table>\n";
  }
  return o + "</section>\n";
}

}  // namespace mutation
}  // namespace plc_cell
