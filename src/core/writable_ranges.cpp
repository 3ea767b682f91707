#include "plc_cell/core/writable_ranges.h"

#include "plc_cell/core/address.h"
#include "plc_cell/core/error.h"

namespace plc_cell {

WritableRanges WritableRanges::parse(const std::string& spec) {
  WritableRanges w;
  std::string s = spec;
  for (char& c : s)
    if (c == ',') c = ' ';
  std::vector<std::string> items;
  for (size_t i = 0; i < s.size();) {
    const size_t j = s.find(' ', i);
    const std::string t = s.substr(i, j == std::string::npos ? std::string::npos : j - i);
    if (!t.empty()) items.push_back(t);
    if (j == std::string::npos) break;
    i = j + 1;
  }
  if (items.size() == 1 && items[0] == "all") return w;
  w.all_ = false;
  if (items.size() == 1 && items[0] == "none") return w;
  if (items.empty()) throw Error("writable ranges: empty (write 'none' for read-only, 'all' for everything)");
  for (const auto& t : items) {
    const auto dash = t.find('-');
    Address a, b;
    std::string why;
    if (!try_parse_address(t.substr(0, dash), &a, &why) ||
        (dash != std::string::npos && !try_parse_address(t.substr(dash + 1), &b, &why)))
      throw Error("writable range '" + t + "': " + why);
    if (dash == std::string::npos) b = a;
    if (a.area != b.area || b.index < a.index)
      throw Error("writable range '" + t + "': both ends must name the same area, low end first (D0-D99)");
    w.ranges_.push_back({a.area, a.index, b.index});
  }
  return w;
}

bool WritableRanges::allows(Area a, uint32_t first, uint32_t count) const {
  if (all_) return true;
  if (count == 0) return true;
  const uint64_t last = uint64_t(first) + count - 1;
  // A request may span adjacent ranges: walk it element by element range by range.
  uint64_t next = first;
  bool progress = true;
  while (next <= last && progress) {
    progress = false;
    for (const auto& r : ranges_)
      if (r.area == a && r.first <= next && next <= r.last) {
        next = uint64_t(r.last) + 1;
        progress = true;
      }
  }
  return next > last;
}

std::string WritableRanges::describe() const {
  if (all_) return "all";
  if (ranges_.empty()) return "none";
  std::string s;
  for (const auto& r : ranges_) {
    if (!s.empty()) s += ",";
    s += std::string(area_name(r.area)) + std::to_string(r.first);
    if (r.last != r.first) s += "-" + std::string(area_name(r.area)) + std::to_string(r.last);
  }
  return s;
}

}  // namespace plc_cell
