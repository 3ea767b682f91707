#pragma once
// The positioning subsystem as a cell extension: the `axes:` section, FUN140-143 and the
// MPG and interpolation FUNs, and the MotionUnit driving PSO0-PSO3 (its pins and encoders
// are the counters' edge sources, so it attaches after the counters extension).
// Facets: the MotionUnit, and the probes axis.NAME.position, .frequency, .state (AxisProbes).
#include <memory>

#include "plc_cell/config/cell_extension.h"
#include "plc_cell/motion/axes_online_check.h"
#include "plc_cell/motion/axis_probes.h"
#include "plc_cell/motion/motion_unit.h"

namespace plc_cell {
namespace motion {

class AxesExtension : public CellExtension {
 public:
  std::string name() const override { return "axes"; }
  std::vector<std::string> sections() const override { return {"axes"}; }
  void install(const CellConfig& cfg, FunctionTable& t) override;
  // An axes: section in error leaves every axis unconfigured (FUN140 still runs them).
  void attach(const CellConfig& cfg, Plc& plc, ErrorList& errors) override;
  std::vector<ExtensionStatus> status(Plc& plc) const override;
  void detach(Plc& plc) override;

  // Only touch it under plc.locked(): the scan calls into it.
  MotionUnit& unit() { return *unit_; }

 private:
  std::unique_ptr<MotionUnit> unit_;
  std::unique_ptr<AxisProbes> probes_;
  std::unique_ptr<AxesOnlineCheck> online_check_;
};

}  // namespace motion
}  // namespace plc_cell
