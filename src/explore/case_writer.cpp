#include "plc_cell/explore/case_writer.h"

#include <filesystem>
#include <sstream>

namespace plc_cell {
namespace explore {

namespace {

namespace fs = std::filesystem;

// Relative to the case file's folder when it is below it, else absolute.
std::string relative_to(const std::string& path, const std::string& out_path) {
  if (path.empty()) return path;
  const fs::path dir = fs::absolute(fs::path(out_path)).parent_path().lexically_normal();
  const fs::path abs = fs::absolute(fs::path(path)).lexically_normal();
  const fs::path rel = abs.lexically_relative(dir);
  for (const auto& part : rel)
    if (part == "..") return abs.string();
  return rel.empty() ? abs.string() : rel.string();
}

// A scalar as YAML reads it back: plain when nothing in it means something to YAML.
std::string scalar(const std::string& s) {
  if (s.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_. <>=!-+/") ==
          std::string::npos &&
      !s.empty() && s[0] != '-' && s[0] != '!')
    return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' || c == '\\' ? std::string("\\") + c : std::string(1, c);
  return q + "\"";
}

}  // namespace

std::string duration_text(uint64_t us) {
  if (us % 1000) return std::to_string(us) + "us";
  if (us < 1000000) return std::to_string(us / 1000) + "ms";
  std::string s = std::to_string(us / 1000000);
  const uint64_t ms = us / 1000 % 1000;
  if (ms) {
    std::string frac = std::to_string(1000 + ms).substr(1);
    while (frac.back() == '0') frac.pop_back();
    s += "." + frac;
  }
  return s + "s";
}

std::string case_file(const scenario::Scenario& sc, const InputRun& run, const std::string& name,
                      const std::string& out_path, const std::string& comment) {
  std::ostringstream o;
  std::istringstream lines(comment);
  for (std::string l; std::getline(lines, l);) o << "# " << l << "\n";
  if (!sc.line.empty()) o << "line: " << scalar(relative_to(sc.line, out_path)) << "\n";
  else o << "cell: " << scalar(relative_to(sc.cell, out_path)) << "\n";
  if (!sc.program.empty()) o << "program: " << scalar(relative_to(sc.program, out_path)) << "\n";
  o << "properties:\n";
  for (const auto& p : sc.properties) {
    const auto colon = p.text.find(": ");
    o << "  - " << p.text.substr(0, colon) << ": " << scalar(p.text.substr(colon + 2)) << "\n";
    if (p.within_us) o << "    within: " << duration_text(p.within_us) << "\n";
  }
  o << "cases:\n  - name: " << scalar(name) << "\n    steps:\n";
  const auto& inputs = sc.explore.inputs;
  auto set = [&](const std::vector<std::pair<size_t, double>>& values) {
    o << "set: {";
    for (size_t i = 0; i < values.size(); ++i)
      o << (i ? ", " : "") << scalar(inputs[values[i].first].probe.text) << ": "
        << value_text(inputs[values[i].first], values[i].second);
    o << "}\n";
  };
  std::vector<std::pair<size_t, double>> first;
  for (size_t i = 0; i < inputs.size(); ++i) first.push_back({i, inputs[i].lo});
  o << "      - ";
  set(first);
  for (size_t i = 0; i < run.changes.size();) {
    std::vector<std::pair<size_t, double>> now;
    const uint64_t t = run.changes[i].t_us;
    for (; i < run.changes.size() && run.changes[i].t_us == t; ++i) now.push_back({run.changes[i].input, run.changes[i].value});
    o << "      - at: " << duration_text(t) << "\n        ";
    set(now);
  }
  o << "      - at: " << duration_text(run.end_us) << "\n";
  return o.str();
}

}  // namespace explore
}  // namespace plc_cell
