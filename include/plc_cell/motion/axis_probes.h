#pragma once
// The axes' scenario probes (config/probe_facet.h): "axis.NAME.position" (pulses),
// ".frequency" (Hz, signed by the direction) and ".state" (idle, moving or error).
#include "plc_cell/config/probe_facet.h"

namespace plc_cell {
namespace motion {

class MotionUnit;

class AxisProbes : public ProbeFacet {
 public:
  explicit AxisProbes(MotionUnit* unit) : unit_(unit) {}
  std::vector<std::string> families() const override { return {"axis"}; }
  std::string check(Plc& plc, const ProbeRef& p, bool writing) const override;
  ProbeReading read(Plc& plc, const ProbeRef& p) const override;

 private:
  MotionUnit* unit_;
};

}  // namespace motion
}  // namespace plc_cell
