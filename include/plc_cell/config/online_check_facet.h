#pragma once
// What an extension forbids a program change in RUN to do with its own state
// (docs/online-change.md, "What a change may not do in RUN"): e.g. the motion unit refuses to
// lose the FUN140 of an axis that is moving. Declared with provide<OnlineCheckFacet>(...);
// the change service asks every extension's with the PLC lock held, right before the swap.
#include <string>
#include <vector>

#include "plc_cell/core/program.h"

namespace plc_cell {

class OnlineCheckFacet {
 public:
  virtual ~OnlineCheckFacet() = default;
  // One line per thing next may not do while running runs (empty: it may).
  virtual std::vector<std::string> refusals(const Program& running, const Program& next) const = 0;
};

}  // namespace plc_cell
