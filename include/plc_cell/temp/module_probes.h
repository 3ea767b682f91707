#pragma once
// The modules' scenario probes (config/probe_facet.h): "temperature.CHANNEL" (read in degC,
// driven in C or the sensor's mV or ohm) and "analog.CHANNEL" (driven in V or mA; its value
// is read from its register).
#include "plc_cell/config/probe_facet.h"

namespace plc_cell {
namespace temp {

class TemperatureCell;

class ModuleProbes : public ProbeFacet {
 public:
  explicit ModuleProbes(TemperatureCell* cell) : cell_(cell) {}
  std::vector<std::string> families() const override { return {"temperature", "analog"}; }
  std::string check(Plc& plc, const ProbeRef& p, bool writing) const override;
  ProbeReading read(Plc& plc, const ProbeRef& p) const override;
  void drive(Plc& plc, const ProbeRef& p, const ProbeInput& v) const override;

 private:
  TemperatureCell* cell_;  // nullptr: the cell has no modules
};

}  // namespace temp
}  // namespace plc_cell
