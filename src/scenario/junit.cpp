#include "plc_cell/scenario/junit.h"

#include <cstdio>
#include <map>

namespace plc_cell {
namespace scenario {

namespace {

std::string escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default:
        // XML 1.0 has no place for other control characters.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t') o += '?';
        else o += c;
    }
  }
  return o;
}

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

void write_junit(const std::vector<CaseResult>& results, std::ostream& out) {
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
  out << "<testsuites name=\"plc_cell test\" tests=\"" << results.size() << "\" failures=\"" << failures
      << "\" errors=\"0\" time=\"" << seconds(total) << "\">\n";
  for (const auto& f : files) {
    const auto& rs = by_file[f];
    size_t fail = 0;
    uint64_t t = 0;
    for (const auto* r : rs) fail += !r->passed, t += r->virtual_us;
    out << "  <testsuite name=\"" << escape(suite_name(f)) << "\" file=\"" << escape(f) << "\" tests=\""
        << rs.size() << "\" failures=\"" << fail << "\" errors=\"0\" skipped=\"0\" time=\"" << seconds(t) << "\">\n";
    for (const auto* r : rs) {
      out << "    <testcase classname=\"" << escape(suite_name(f)) << "\" name=\"" << escape(r->name) << "\" file=\""
          << escape(f) << "\" line=\"" << r->line << "\" time=\"" << seconds(r->virtual_us) << "\"";
      if (r->passed) {
        out << "/>\n";
        continue;
      }
      out << ">\n      <failure message=\"" << escape(r->failure) << "\">" << escape(r->failure + "\n" + r->details)
          << "</failure>\n    </testcase>\n";
    }
    out << "  </testsuite>\n";
  }
  out << "</testsuites>\n";
}

}  // namespace scenario
}  // namespace plc_cell
