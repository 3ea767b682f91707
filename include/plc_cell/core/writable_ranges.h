#pragma once
// Which addresses a network client (FATEK, Modbus) may write: the protocols have no
// authentication, so this is how a deployment keeps them off the rest of the memory
// (docs/security.md). Default: everything writable, as a real FBs.
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/core/memory.h"

namespace plc_cell {

class WritableRanges {
 public:
  WritableRanges() = default;  // everything writable
  // "D0-D99,M800-M899,Y0" (commas or spaces), "none" (read-only) or "all". Throws Error.
  static WritableRanges parse(const std::string& spec);

  // Elements first..first+count-1 of area a (registers: 16-bit elements).
  bool allows(Area a, uint32_t first, uint32_t count = 1) const;
  bool everything() const { return all_; }
  std::string describe() const;

 private:
  bool all_ = true;
  std::vector<AreaRange> ranges_;
};

}  // namespace plc_cell
