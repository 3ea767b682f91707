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

// "survived: no case checks it (executed by: a; b)"
std::string why(const ProgramResult& p, const MutantResult& r) {
  const auto& by = executed(p, r.mutant.line);
  if (r.verdict == Verdict::Equivalent)
    return "equivalent-suspect: every probed value is the same at every scan of every case";
  if (by.empty()) return "survived: no case executes it";
  if (by.size() == p.cases) return "survived: no case checks it (executed by every case)";
  std::string s = "survived: no case checks it (executed by: ";
  for (size_t i = 0; i < by.size(); ++i) s += (i ? "; " : "") + by[i];
  return s + ")";
}

std::vector<Score> per_network(const ProgramResult& p) {
  std::vector<Score> s(p.networks.size() + 1);
  for (const auto& r : p.results) {
    Score& n = s[network_of(p, r.mutant.line)];
    (r.verdict == Verdict::Killed ? n.killed : r.verdict == Verdict::Survived ? n.survived
     : r.verdict == Verdict::Equivalent ? n.equivalent : n.not_loaded)++;
  }
  return s;
}

}  // namespace

Score score(const std::vector<MutantResult>& results) {
  Score s;
  for (const auto& r : results)
    (r.verdict == Verdict::Killed ? s.killed : r.verdict == Verdict::Survived ? s.survived
     : r.verdict == Verdict::Equivalent ? s.equivalent : s.not_loaded)++;
  return s;
}

uint32_t network_of(const ProgramResult& p, int line) {
  for (const auto& n : p.networks)
    if (line >= n.line && line <= n.end_line) return n.number;
  return 0;
}

void write_text(const std::vector<ProgramResult>& programs, std::ostream& out) {
  for (const auto& p : programs) {
    const Score s = score(p.results);
    out << "mutation testing of " << p.program << ": " << p.results.size() << " mutants";
    if (p.results.size() < p.generated) out << " (of " << p.generated << ")";
    out << ", " << p.cases << (p.cases == 1 ? " case" : " cases") << " each\n  killed " << s.killed << ", survived " << s.survived
        << ", equivalent-suspect " << s.equivalent << ", not loaded " << s.not_loaded << ": score "
        << percent(s.score()) << "\n";
    const auto nets = per_network(p);
    for (const auto& n : p.networks) {
      const Score& ns = nets[n.number];
      if (ns.killed + ns.survived + ns.equivalent == 0) continue;
      out << "  network " << n.number << " (line " << n.line << "): " << ns.killed << "/" << ns.killed + ns.survived
          << " killed" << (ns.equivalent ? ", " + std::to_string(ns.equivalent) + " equivalent-suspect" : "") << "\n";
    }
    for (const auto& r : p.results)
      if (r.verdict == Verdict::Survived || r.verdict == Verdict::Equivalent)
        out << p.program << ":" << r.mutant.line << ": " << r.mutant.change() << " " << why(p, r) << "\n";
  }
}

void write_json(const std::vector<ProgramResult>& programs, std::ostream& out) {
  out << "{\"programs\": [";
  for (size_t i = 0; i < programs.size(); ++i) {
    const ProgramResult& p = programs[i];
    const Score s = score(p.results);
    out << (i ? ", " : "") << "\n  {\"file\": " << json_string(p.program) << ", \"cases\": " << p.cases
        << ", \"generated\": " << p.generated << ", \"mutants\": " << p.results.size() << ", \"killed\": " << s.killed
        << ", \"survived\": " << s.survived << ", \"equivalent_suspect\": " << s.equivalent
        << ", \"not_loaded\": " << s.not_loaded << ", \"score\": " << s.score() << ",\n   \"networks\": [";
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
      out << (k ? "," : "") << "\n    {\"line\": " << r.mutant.line << ", \"network\": " << network_of(p, r.mutant.line)
          << ", \"operator\": " << json_string(r.mutant.op) << ", \"from\": " << json_string(r.mutant.before)
          << ", \"to\": " << json_string(r.mutant.after) << ", \"status\": " << json_string(verdict_name(r.verdict))
          << ", \"killed_by\": " << (r.killed_by.empty() ? "null" : json_string(r.killed_by)) << ", \"executed_by\": [";
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
    const Score s = score(p.results);
    o += "<h3>" + html(p.program) + "</h3>\n<p>" + std::to_string(p.results.size()) + " mutants, killed " +
         std::to_string(s.killed) + ", survived " + std::to_string(s.survived) + ", equivalent-suspect " +
         std::to_string(s.equivalent) + ", not loaded " + std::to_string(s.not_loaded) + ": score " +
         html(percent(s.score())) + "</p>\n<table class=\"summary\">\n<tr><th>line</th><th>network</th>"
         "<th>mutant</th><th>status</th></tr>\n";
    for (const auto& r : p.results) {
      const bool bad = r.verdict == Verdict::Survived || r.verdict == Verdict::Equivalent;
      o += "<tr class=\"" + std::string(bad ? "bad" : "ok") + "\"><td>" + std::to_string(r.mutant.line) + "</td><td>" +
           std::to_string(network_of(p, r.mutant.line)) + "</td><td>" + html(r.mutant.change()) + "</td><td>" +
           html(bad ? why(p, r) : std::string(verdict_name(r.verdict)) +
                                     (r.killed_by.empty() ? "" : " by " + r.killed_by)) + "</td></tr>\n";
    }
    o += "</table>\n";
  }
  return o + "</section>\n";
}

}  // namespace mutation
}  // namespace plc_cell
