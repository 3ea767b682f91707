#pragma once
// What a program change in RUN may not do to the pulse axes (docs/online-change.md): take away
// the FUN140 of an axis whose positioning table is running, or point it at another table.
// The motion unit would go on pulsing with no instruction left to pause, abort or finish it.
#include <string>
#include <vector>

#include "plc_cell/config/online_check_facet.h"

namespace plc_cell {
namespace motion {

class MotionUnit;

class AxesOnlineCheck : public OnlineCheckFacet {
 public:
  explicit AxesOnlineCheck(const MotionUnit* unit) : unit_(unit) {}
  std::vector<std::string> refusals(const plc_cell::Program& running, const plc_cell::Program& next) const override;

 private:
  const MotionUnit* unit_;
};

}  // namespace motion
}  // namespace plc_cell
