#include <cctype>
#include <cstdlib>
#include <set>
#include <sstream>

#include "plc_cell/mutation/mutant.h"

namespace plc_cell {
namespace mutation {

namespace {

std::string upper(std::string s) {
  for (char& c : s) c = char(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string join(const std::vector<std::string>& t) {
  std::string s;
  for (const auto& w : t) s += (s.empty() ? "" : " ") + w;
  return s;
}

bool integer(const std::string& s, long long* v) {
  if (s.empty()) return false;
  char* end = nullptr;
  *v = std::strtoll(s.c_str(), &end, 10);
  return *end == '\0' && (std::isdigit(static_cast<unsigned char>(s[0])) || s[0] == '-');
}

// The mutants of one instruction (its words), each as its new words (empty: deleted).
class LineMutants {
 public:
  explicit LineMutants(const std::vector<std::string>& t) : t_(t), m_(upper(t[0])) {}

  void contact() {
    if (m_ != "ORG" && m_ != "LD" && m_ != "AND" && m_ != "OR") return;
    const std::string mod = t_.size() > 2 ? upper(t_[1]) : "";
    if (t_.size() != (mod.empty() ? 2u : 3u)) return;
    if (!mod.empty() && mod != "NOT" && mod != "TU" && mod != "TD") return;
    const std::string& operand = t_.back();
    if (mod.empty()) add("invert contact", {t_[0], "NOT", operand});
    if (mod == "NOT") add("invert contact", {t_[0], operand});
    if (m_ == "AND" || m_ == "OR") {
      std::vector<std::string> o = t_;
      o[0] = m_ == "AND" ? "OR" : "AND";
      add("AND/OR", o);
    }
    if (mod == "TU" || mod == "TD") {
      add("edge", {t_[0], mod == "TU" ? "TD" : "TU", operand});
      add("edge", {t_[0], operand});
    }
    if (mod.empty()) add("edge", {t_[0], "TU", operand});
  }

  void blocks_and_coils() {
    if (t_.size() == 1 && (m_ == "ANDLD" || m_ == "ORLD")) add("ANDLD/ORLD", {m_ == "ANDLD" ? "ORLD" : "ANDLD"});
    if ((m_ == "SET" || m_ == "RST") && t_.size() == 2 && std::string("YMS").find(char(std::toupper(t_[1][0]))) != std::string::npos)
      add("SET/RST", {m_ == "SET" ? "RST" : "SET", t_[1]});
    if (m_ == "OUT" || m_ == "SET" || m_ == "RST") add("delete coil", {});
  }

  void preset() {
    long long n;
    if ((m_ != "TMR" && m_ != "CTR") || t_.size() != 3 || !integer(t_[2], &n)) return;
    for (long long v : {n + 1, n - 1, n * 2, n / 2}) {
      if (v <= 0 || v > 32767 || v == n) continue;
      std::vector<std::string> o = t_;
      o[2] = std::to_string(v);
      add("preset", o);
    }
  }

  void fun() {
    if (m_ != "FUN") return;
    const bool cmp = t_.size() > 2 && upper(t_[2]) == "CMP";
    std::set<std::string> flags;
    for (const auto& w : t_) flags.insert(upper(w.substr(0, w.find('='))));
    for (size_t i = 1; i < t_.size(); ++i) {
      const auto eq = t_[i].find('=');
      if (eq == std::string::npos) continue;
      const std::string key = upper(t_[i].substr(0, eq)), value = t_[i].substr(eq + 1);
      long long n;
      if (integer(value, &n))
        for (long long v : {n + 1, n - 1}) operand(i, t_[i].substr(0, eq + 1) + std::to_string(v), "constant");
      if (!cmp || (key != "EQ" && key != "GT" && key != "LT")) continue;
      for (const char* other : {"EQ", "GT", "LT"})
        if (!flags.count(other)) operand(i, std::string(other) + "=" + value, "comparison");
    }
  }

  std::vector<std::pair<std::string, std::vector<std::string>>> out;

 private:
  void operand(size_t i, const std::string& word, const char* op) {
    std::vector<std::string> o = t_;
    o[i] = word;
    add(op, o);
  }
  void add(const char* op, const std::vector<std::string>& words) { out.push_back({op, words}); }

  const std::vector<std::string>& t_;
  const std::string m_;
};

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line.substr(0, line.find(';')));
  std::vector<std::string> t;
  for (std::string w; in >> w;) t.push_back(w);
  return t;
}

}  // namespace

std::vector<Mutant> mutants(const std::vector<std::string>& lines) {
  std::vector<Mutant> out;
  for (size_t n = 0; n < lines.size(); ++n) {
    const std::vector<std::string> t = words(lines[n]);
    if (t.empty()) continue;
    LineMutants lm(t);
    lm.contact();
    lm.blocks_and_coils();
    lm.preset();
    lm.fun();
    std::set<std::string> seen;
    for (const auto& [op, w] : lm.out) {
      const std::string after = join(w);
      if (!seen.insert(after).second) continue;
      out.push_back({int(n + 1), op, join(t), after});
    }
  }
  return out;
}

std::string apply(const std::vector<std::string>& lines, const Mutant& m) {
  std::string text;
  for (size_t n = 0; n < lines.size(); ++n)
    text += (int(n + 1) == m.line ? m.after : lines[n]) + "\n";
  return text;
}

}  // namespace mutation
}  // namespace plc_cell
