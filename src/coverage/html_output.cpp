#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "plc_cell/core/error.h"
#include "plc_cell/coverage/outputs.h"
#include "ratio_text.h"

namespace plc_cell {
namespace coverage {

namespace {

// The page is opened from disk, often where there is no network: styles are inline and
// nothing is fetched. The colours are the legend's; test/coverage checks them in a browser,
// and that at 900 px nothing runs off the page: long comments and notes wrap, never cut.
const char* const kStyle = R"(body{font-family:sans-serif;margin:1.5em;color:#222}
table.summary{border-collapse:collapse;margin-bottom:1em}
table.summary th,table.summary td{border:1px solid #bbb;padding:.2em .6em;text-align:right}
table.summary{max-width:100%}
table.summary th:first-child,table.summary td:first-child{text-align:left;min-width:12em;overflow-wrap:anywhere}
h2,.findings,.error{overflow-wrap:anywhere}
.legend span{display:inline-block;padding:.1em .6em;margin-right:.6em;border:1px solid #bbb}
.findings{font-family:monospace}
.error{color:#a00}
.listing{font-family:monospace;font-size:13px}
.net{margin:.4em 0;border-left:6px solid}
.net>.head{font-family:sans-serif;font-weight:bold;padding:.15em .5em}
.net.ok{background:#e8f7e8;border-color:#2e7d32}
.net.bad{background:#fbe3e3;border-color:#c62828}
.net.off{background:#efefef;border-color:#9e9e9e}
.gap{border-left:6px solid transparent}
.line{display:flex;align-items:baseline}
.line.ok{background:#b9e8b9}
.line.bad{background:#f5b5b5}
.line.off{background:#d6d6d6}
.no{width:4em;text-align:right;color:#777;padding-right:1em;flex:none}
.code{flex:none;width:18em;white-space:pre-wrap;overflow-wrap:anywhere}
.comment{color:#666;flex:1 1 24em;min-width:8em;white-space:pre-wrap;overflow-wrap:anywhere}
.note{font-family:sans-serif;font-style:italic;flex:0 1 18em;min-width:8em;padding-left:.6em;overflow-wrap:anywhere}
@media (max-width:700px){.line{flex-wrap:wrap}.code{width:auto;flex:1 1 12em}.comment,.note{flex-basis:100%;padding-left:5em}}
)";

std::string escape(const std::string& s) {
  std::string e;
  for (const char c : s) {
    switch (c) {
      case '&': e += "&amp;"; break;
      case '<': e += "&lt;"; break;
      case '>': e += "&gt;"; break;
      case '"': e += "&quot;"; break;
      default: e += c;
    }
  }
  return e;
}

// As the IL lexer reads a line: ';' or '//' starts the comment.
std::pair<std::string, std::string> split_comment(const std::string& line) {
  size_t at = line.find(';');
  const size_t slashes = line.find("//");
  if (slashes < at) at = slashes;
  if (at == std::string::npos) return {line, ""};
  return {line.substr(0, at), line.substr(at)};
}

const char* state_class(const Item& it) { return it.exercised() ? "ok" : it.evaluated() ? "bad" : "off"; }

std::string note(const Item& it) {
  if (!it.evaluated()) return "not evaluated";
  const std::string level = it.seen_on ? "ON" : "OFF";
  switch (it.kind) {
    case ItemKind::Contact:
      return it.exercised() ? label(it) + " seen OFF and ON" + (it.mcdc ? "; MC/DC shown" : "; MC/DC not shown")
                            : "never changed: " + label(it) + " always " + level;
    case ItemKind::Coil:
      return it.exercised() ? "switched: rung OFF and ON" : "never switched: rung always " + level;
    case ItemKind::Fun:
      return it.exercised() ? "enabled" : "never enabled";
  }
  return "";
}

void summary_row(const Report& r, size_t p, std::ostream& out) {
  const Totals& t = r.totals;
  out << "<tr><td><a href=\"#p" << p << "\">" << escape(r.file) << "</a></td><td>" << r.runs << "</td><td>"
      << ratio(t.networks_evaluated, t.networks) << "</td><td>" << ratio(t.networks_energised, t.networks)
      << "</td><td>" << ratio(t.contacts_changed, t.contacts) << "</td><td>" << ratio(t.contacts_mcdc, t.contacts)
      << "</td><td>" << ratio(t.coils_switched, t.coils)
      << "</td><td>" << ratio(t.funs_enabled, t.funs) << "</td></tr>\n";
}

void line_html(const Report& r, size_t p, int n, const Item* item, std::ostream& out) {
  const std::string text = static_cast<size_t>(n) <= r.source.size() ? r.source[static_cast<size_t>(n) - 1] : "";
  const auto parts = split_comment(text);
  out << "<div class=\"line" << (item ? std::string(" ") + state_class(*item) : "") << "\" id=\"p" << p << "-l" << n
      << "\"><span class=\"no\">" << n << "</span><span class=\"code\">" << escape(parts.first)
      << "</span><span class=\"comment\">" << escape(parts.second) << "</span>";
  if (item) out << "<span class=\"note\">" << escape(note(*item)) << "</span>";
  out << "</div>\n";
}

void network_head(const Network& n, std::ostream& out) {
  const char* cls = !n.evaluated ? "off" : n.energised ? "ok" : "bad";
  out << "<div class=\"net " << cls << "\" data-network=\"" << n.number << "\"><div class=\"head\">network "
      << n.number << " (line " << n.line << ")";
  if (!n.routine.empty()) out << " in " << escape(n.routine);
  out << ": " << (!n.evaluated ? "not evaluated" : n.energised ? "energised" : "never energised") << "</div>\n";
}

void program_html(const Report& r, size_t p, std::ostream& out) {
  out << "<section class=\"program\" id=\"p" << p << "\">\n<h2>" << escape(r.file) << "</h2>\n";
  if (!r.source_error.empty())
    out << "<p class=\"error\">" << escape(r.source_error) << "; the instructions are shown as parsed.</p>\n";
  out << "<h3>Findings</h3>\n";
  if (r.findings.empty()) out << "<p>Every network, contact, coil and FUN was exercised.</p>\n";
  else out << "<ul class=\"findings\">\n";
  for (const Finding& f : r.findings)
    out << "<li><a href=\"#p" << p << "-l" << f.line << "\">" << escape(r.file) << ':' << f.line << "</a> "
        << escape(f.message) << "</li>\n";
  if (!r.findings.empty()) out << "</ul>\n";
  out << "<h3>Program</h3>\n<div class=\"listing\">\n";

  std::map<int, const Item*> item_at;
  int last = static_cast<int>(r.source.size());
  for (const Network& n : r.networks) {
    last = std::max(last, n.end_line);
    for (const Item& it : n.items) item_at[it.line] = &it;
  }
  size_t next = 0;  // the next network to open
  int line = 1;
  while (line <= last) {
    if (next < r.networks.size() && r.networks[next].line == line) {
      const Network& n = r.networks[next++];
      network_head(n, out);
      for (; line <= n.end_line; ++line) {
        const auto it = item_at.find(line);
        line_html(r, p, line, it == item_at.end() ? nullptr : it->second, out);
      }
      out << "</div>\n";
      continue;
    }
    const int gap_end = next < r.networks.size() ? r.networks[next].line - 1 : last;
    out << "<div class=\"gap\">\n";
    for (; line <= gap_end; ++line) line_html(r, p, line, nullptr, out);
    out << "</div>\n";
  }
  out << "</div>\n</section>\n";
}

}  // namespace

void write_html(const std::vector<Report>& reports, const std::string& dir, const std::string& extra) {
  std::ostringstream page;
  page << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       << "<title>Rung coverage</title>\n<style>\n" << kStyle << "</style>\n</head>\n<body>\n"
       << "<h1>Rung coverage</h1>\n<table class=\"summary\">\n"
       << "<tr><th>program</th><th>runs</th><th>networks evaluated</th><th>energised</th>"
       << "<th>contacts changed</th><th>MC/DC</th><th>coils switched</th><th>FUNs enabled</th></tr>\n";
  for (size_t p = 0; p < reports.size(); ++p) summary_row(reports[p], p + 1, page);
  page << "</table>\n<p class=\"legend\"><span class=\"line ok\">exercised: energised, changed, switched, enabled</span>"
       << "<span class=\"line bad\">never energised, changed, switched or enabled</span>"
       << "<span class=\"line off\">not evaluated</span></p>\n";
  for (size_t p = 0; p < reports.size(); ++p) program_html(reports[p], p + 1, page);
  page << extra << "</body>\n</html>\n";

  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error("coverage: cannot create " + dir + ": " + ec.message());
  const std::string path = (std::filesystem::path(dir) / "index.html").string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << page.str();
  out.flush();
  if (!out) throw Error("coverage: cannot write " + path + ": " + std::strerror(errno));
}

}  // namespace coverage
}  // namespace plc_cell
