#include "plc_cell/core/interrupt_sources.h"

#include <unordered_map>

namespace plc_cell {
namespace irq {

std::vector<std::string> source_labels(int s) {
  static const char* const tb[8] = {"1MS", "2MS", "3MS", "4MS", "5MS", "10MS", "50MS", "100MS"};
  if (s == kHstaI) return {"HSTAI", "ATMRI"};
  if (s >= kTimeBase0 && s < kHsc0I) {
    const std::string b = tb[s - kTimeBase0];
    return {b + "I", b};
  }
  if (s >= kHsc0I && s < kPso0I) {
    const std::string n = std::to_string(s - kHsc0I);
    return {"HSC" + n + "I", "HST" + n + "I"};
  }
  if (s >= kPso0I && s < kX0Up) return {"PSO" + std::to_string(s - kPso0I) + "I"};
  if (s >= kX0Up && s < kHsc4I) {
    const int x = (s - kX0Up) / 2;
    const bool falling = (s - kX0Up) % 2;
    const std::string n = std::to_string(x);
    return {"X" + n + (falling ? "-I" : "+I"), "INT" + n + (falling ? "-" : "")};
  }
  if (s >= kHsc4I && s < kSourceCount) return {"HSC" + std::to_string(4 + s - kHsc4I) + "I"};
  return {};
}

int source_of_label(const std::string& label) {
  // Every label of the program is looked up when it loads: the table is built once.
  static const std::unordered_map<std::string, int> table = [] {
    std::unordered_map<std::string, int> t;
    for (int s = 0; s < kSourceCount; ++s)
      for (const auto& l : source_labels(s)) t.emplace(l, s);
    return t;
  }();
  const auto it = table.find(label);
  return it == table.end() ? -1 : it->second;
}

}  // namespace irq
}  // namespace plc_cell
