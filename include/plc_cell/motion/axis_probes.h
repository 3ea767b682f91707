#pragma once
// The axes' scenario probes (config/probe_facet.h): "axis.NAME.position" (pulses),
// ".frequency" (Hz, signed by the direction) and ".state" (idle, moving or error).
#include <cstdint>
#include <string>

#include "plc_cell/config/probe_facet.h"

namespace plc_cell {
namespace motion {

class MotionUnit;

// What an axis probe's field reads from an axis's pulses, signed frequency and error code:
// the state as the axis's status topic shows it (an error code, else pulses going out, else
// idle). One rule for the cell in process and for plc_node's status topic.
ProbeReading axis_reading(const std::string& field, int64_t pulses, double hz, int error);

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
