#pragma once
// The counters' scenario probes (config/probe_facet.h): "counter.NAME" (its count) and
// "pulse.Xn.width", ".period" (in the configured unit), ".frequency" (Hz), the pulse
// measurement of a counter input.
#include "plc_cell/config/probe_facet.h"

namespace plc_cell {
namespace hsc {

class HscUnit;

class CounterProbes : public ProbeFacet {
 public:
  explicit CounterProbes(const HscUnit* unit) : unit_(unit) {}
  std::vector<std::string> families() const override { return {"counter", "pulse"}; }
  std::string check(Plc& plc, const ProbeRef& p, bool writing) const override;
  ProbeReading read(Plc& plc, const ProbeRef& p) const override;

 private:
  const HscUnit* unit_;
};

}  // namespace hsc
}  // namespace plc_cell
