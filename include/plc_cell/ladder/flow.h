#pragma once
// Live power flow through a laid-out network, computed from memory values: the same
// boolean the interpreter computes, shown as which elements and wires carry power.
#include <cstdint>
#include <functional>
#include <map>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/ladder/layout.h"

namespace plc_cell {
namespace ladder {

// The value of an address in one frame (a bit is 0 or 1).
using Lookup = std::function<uint32_t(const Address&)>;

struct Flow {
  int net = 0;
  std::vector<int> on;  // energised element and wire ids, ascending
};

// Energised ids: a contact that passes power, a wire carrying power, an output whose
// input is powered. TU/TD contacts are closed when their bit rose/fell from prev to now
// (edge memories are not readable: the previous frame stands in for them).
Flow flow(const Network& network, const Lookup& now, const Lookup& prev);

// A frame's values by address, for building a Lookup (missing addresses read 0).
class Values {
 public:
  void set(const Address& a, uint32_t v);
  uint32_t get(const Address& a) const;
  Lookup lookup() const {
    return [this](const Address& a) { return get(a); };
  }

 private:
  std::map<uint64_t, uint32_t> values_;
};

}  // namespace ladder
}  // namespace plc_cell
