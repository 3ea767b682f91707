#include "cell_draft.h"

#include <algorithm>

#include "cell_part.h"

namespace plc_cell_fuzz {

std::string hex(uint32_t v) {
  std::ostringstream o;
  o << "0x" << std::hex << std::uppercase << v;
  return o.str();
}

std::string indent(const std::string& text, int n) {
  std::string o, pad(n, ' ');
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) o += pad + l + "\n";
  return o;
}

std::string seconds(Fdp& f) { return std::to_string(f.ConsumeIntegralInRange<int>(0, 3000) / 1000.0); }

int Pins::take(Fdp& f, int lo, int hi) {
  if (chance(f, 64)) return f.ConsumeIntegralInRange<int>(lo, hi);
  for (int tries = 0; tries < 8; ++tries) {
    const int x = f.ConsumeIntegralInRange<int>(lo, hi);
    if (!used[x]) {
      used[x] = true;
      return x;
    }
  }
  return -1;
}

bool Pins::claim(int x) {
  if (used[x]) return false;
  used[x] = true;
  return true;
}

std::ostringstream& CellDraft::section(const std::string& name) {
  for (auto& s : sections_)
    if (s.first == name) return s.second;
  sections_.emplace_back(name, std::ostringstream());
  return sections_.back().second;
}

namespace {
std::vector<CellPart>& registry() {
  static std::vector<CellPart> parts;
  return parts;
}
}  // namespace

const std::vector<CellPart>& cell_parts() { return registry(); }

RegisterCellPart::RegisterCellPart(CellPart part) {
  auto& parts = registry();
  parts.insert(std::upper_bound(parts.begin(), parts.end(), part,
                                [](const CellPart& a, const CellPart& b) { return a.order < b.order; }),
               std::move(part));
}

}  // namespace plc_cell_fuzz
