#include "plc_cell/scenario/junit.h"

#include <cstdio>
#include <map>

#include "plc_cell/core/utf8.h"

namespace plc_cell {
namespace scenario {

namespace {

// XML 1.0 has room for these characters only (section 2.2, Char).
bool xml_char(char32_t c) {
  return c == '\t' || c == '\n' || c == '\r' || (c >= 0x20 && c <= 0xD7FF) || (c >= 0xE000 && c <= 0xFFFD) ||
         (c >= 0x10000 && c <= 0x10FFFF);
}

// s as XML character data, or an attribute's value (in double quotes), well-formed whatever
// bytes s holds: a name or a path can carry any byte, a message any character. A byte that
// is not UTF-8 is shown as \xFF and a character XML cannot hold as \u0001, so the report
// still says which; in an attribute, tab and line breaks are character references, which
// an XML reader keeps (a raw one it would turn into a space).
std::string escape(const std::string& s, bool attribute = false) {
  std::string o;
  char hex[16];
  for (size_t i = 0; i < s.size();) {
    const size_t at = i;
    const char32_t c = utf8::next(s, &i);
    if (c == utf8::kInvalid) {
      std::snprintf(hex, sizeof hex, "\\x%02X", static_cast<unsigned>(static_cast<unsigned char>(s[at])));
      o += hex;
      continue;
    }
    if (!xml_char(c)) {
      std::snprintf(hex, sizeof hex, "\\u%04X", static_cast<unsigned>(c));
      o += hex;
      continue;
    }
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\r': o += "&#13;"; break;
      case '\n': o += attribute ? "&#10;" : "\n"; break;
      case '\t': o += attribute ? "&#9;" : "\t"; break;
      default: o.append(s, at, i - at);
    }
  }
  return o;
}
std::string attr(const std::string& s) { return escape(s, true); }

std::string seconds(uint64_t us) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6f", double(us) / 1e6);
  return b;
}

// "examples/conveyor/conveyor.scenario.yaml" -> "conveyor.scenario": the classname a CI
// page groups the cases under.
std::string suite_name(const std::string& file) {
  std::string base = file.substr(file.rfind('/') == std::string::npos ? 0 : file.rfind('/') + 1);
  const auto dot = base.rfind(".yaml");
  if (dot != std::string::npos) base.resize(dot);
  return base;
}

}  // namespace

void write_junit(const std::vector<CaseResult>& results, std::ostream& out, const JUnitRun& run) {
  const std::string& target = run.target;
  std::vector<std::string> files;
  std::map<std::string, std::vector<const CaseResult*>> by_file;
  for (const auto& r : results) {
    if (!by_file.count(r.file)) files.push_back(r.file);
    by_file[r.file].push_back(&r);
  }
  size_t failures = 0;
  uint64_t total = 0;
  for (const auto& r : results) failures += !r.passed, total += r.virtual_us;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  const std::string on = target.empty() ? "" : " on " + target;
  out << "<testsuites name=\"" << attr("plc_cell test" + (target.empty() ? "" : " --target " + target))
      << "\" tests=\"" << results.size() << "\" failures=\"" << failures
      << "\" errors=\"0\" time=\"" << seconds(total) << "\">\n";
  for (const auto& f : files) {
    const auto& rs = by_file[f];
    size_t fail = 0;
    uint64_t t = 0;
    for (const auto* r : rs) fail += !r->passed, t += r->virtual_us;
    out << "  <testsuite name=\"" << attr(suite_name(f) + on) << "\" file=\"" << attr(f) << "\" tests=\""
        << rs.size() << "\" failures=\"" << fail << "\" errors=\"0\" skipped=\"0\" time=\"" << seconds(t) << "\">\n";
    if (!run.properties.empty()) {
      out << "    <properties>\n";
      for (const auto& p : run.properties)
        out << "      <property name=\"" << attr(p.first) << "\" value=\"" << attr(p.second) << "\"/>\n";
      out << "    </properties>\n";
    }
    for (const auto* r : rs) {
      out << "    <testcase classname=\"" << attr(suite_name(f) + on) << "\" name=\"" << attr(r->name) << "\" file=\""
          << attr(f) << "\" line=\"" << r->line << "\" time=\"" << seconds(r->virtual_us) << "\"";
      if (r->passed) {
        out << "/>\n";
        continue;
      }
      out << ">\n      <failure message=\"" << attr(r->failure) << "\">" << escape(r->failure + "\n" + r->details)
          << "</failure>\n    </testcase>\n";
    }
    out << "  </testsuite>\n";
  }
  out << "</testsuites>\n";
}

}  // namespace scenario
}  // namespace plc_cell
