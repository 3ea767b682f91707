#include "plc_cell/online/il_diff.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <sstream>

namespace plc_cell {
namespace online {

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// One line of the edit script: ' ' kept, '-' removed, '+' added, with its line in each side.
struct Edit {
  char kind;
  size_t a, b;  // 0-based line in old and in next (the side's next line for an add/remove)
};

// Longest common subsequence of the middle (after the common head and tail); a middle too
// large for the table is one block removed and added, which is still a true diff.
std::vector<Edit> edits(const std::vector<std::string>& a, const std::vector<std::string>& b) {
  size_t head = 0;
  while (head < a.size() && head < b.size() && a[head] == b[head]) ++head;
  size_t tail = 0;
  while (tail < a.size() - head && tail < b.size() - head && a[a.size() - 1 - tail] == b[b.size() - 1 - tail]) ++tail;
  const size_t n = a.size() - head - tail, m = b.size() - head - tail;
  std::vector<Edit> out;
  for (size_t i = 0; i < head; ++i) out.push_back({' ', i, i});
  if (n * m <= 4'000'000) {
    std::vector<uint32_t> len((n + 1) * (m + 1), 0);
    auto at = [&](size_t i, size_t j) -> uint32_t& { return len[i * (m + 1) + j]; };
    for (size_t i = n; i-- > 0;)
      for (size_t j = m; j-- > 0;)
        at(i, j) = a[head + i] == b[head + j] ? at(i + 1, j + 1) + 1 : std::max(at(i + 1, j), at(i, j + 1));
    size_t i = 0, j = 0;
    while (i < n || j < m) {
      if (i < n && j < m && a[head + i] == b[head + j]) {
        out.push_back({' ', head + i++, head + j++});
      } else if (j < m && (i == n || at(i, j + 1) >= at(i + 1, j))) {
        out.push_back({'+', head + i, head + j++});
      } else {
        out.push_back({'-', head + i++, head + j});
      }
    }
  } else {
    for (size_t i = 0; i < n; ++i) out.push_back({'-', head + i, head});
    for (size_t j = 0; j < m; ++j) out.push_back({'+', head + n, head + j});
  }
  for (size_t k = 0; k < tail; ++k) out.push_back({' ', a.size() - tail + k, b.size() - tail + k});
  return out;
}

}  // namespace

std::string unified_diff(const std::string& old_text, const std::string& next_text, const std::string& old_name,
                         const std::string& next_name) {
  const auto a = lines_of(old_text), b = lines_of(next_text);
  const std::vector<Edit> e = edits(a, b);
  std::ostringstream out;
  constexpr size_t kContext = 3;
  size_t k = 0;
  bool header = false;
  while (k < e.size()) {
    if (e[k].kind == ' ') {
      ++k;
      continue;
    }
    // A hunk: from kContext lines before this change to kContext after the last change that
    // is at most 2 * kContext kept lines from the one before it.
    const size_t from = k >= kContext ? k - kContext : 0;
    size_t to = k;
    for (size_t j = k; j < e.size(); ++j) {
      if (e[j].kind != ' ') to = j;
      else if (j - to > 2 * kContext) break;
    }
    const size_t end = std::min(e.size(), to + kContext + 1);
    size_t na = 0, nb = 0;
    for (size_t j = from; j < end; ++j) {
      na += e[j].kind != '+';
      nb += e[j].kind != '-';
    }
    if (!header) {
      out << "--- " << old_name << "\n+++ " << next_name << "\n";
      header = true;
    }
    out << "@@ -" << (na ? e[from].a + 1 : e[from].a) << "," << na << " +" << (nb ? e[from].b + 1 : e[from].b) << ","
        << nb << " @@\n";
    for (size_t j = from; j < end; ++j)
      out << e[j].kind << (e[j].kind == '+' ? b[e[j].b] : a[e[j].a]) << "\n";
    k = end;
  }
  return out.str();
}

std::vector<int> changed_lines(const std::string& old_text, const std::string& next_text) {
  std::vector<int> out;
  for (const Edit& e : edits(lines_of(old_text), lines_of(next_text)))
    if (e.kind == '+') out.push_back(int(e.b) + 1);
  return out;
}

std::string text_hash(const std::string& text) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace online
}  // namespace plc_cell
