#include "plc_cell/line/delay_line.h"

#include <algorithm>

namespace plc_cell {
namespace line {

DelayLine::DelayLine(const WireModel& m, uint32_t initial)
    : m_(m), last_(initial), initial_(m.part ? out(0) : out(initial)), covered_until_ns_(0) {}

void DelayLine::sample(uint64_t t_us, uint32_t value, std::vector<WireEdge>* edges) {
  const uint32_t before = last_;
  last_ = value;
  if (value == before) return;
  const uint64_t t_ns = t_us * 1000;
  if (!m_.part) {
    edges->push_back({t_ns + std::max<uint64_t>(m_.delay_ns, 1), out(value)});
    return;
  }
  if (before != 0 || value == 0) return;  // a part is a rising edge
  const uint64_t arrives = t_ns + std::max<uint64_t>(m_.travel_ns, 1), leaves = arrives + m_.length_ns;
  if (covered_until_ns_ != 0 && arrives <= covered_until_ns_) {
    // Still covered by the parts before: the edge that uncovers the sensor when they leave
    // is already handed on; one at the same instant after it keeps the sensor covered.
    edges->push_back({covered_until_ns_, out(1)});
  } else {
    edges->push_back({arrives, out(1)});
  }
  edges->push_back({leaves, out(0)});
  covered_until_ns_ = leaves;
}

}  // namespace line
}  // namespace plc_cell
