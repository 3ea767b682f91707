#pragma once
// The counters subsystem as a cell extension: the `counters:` section, FUN92/93/145/146/74,
// and the HscUnit (counters, timers, interrupts and the exact-time edges of X0-X15).
// Facets: the HscUnit, and the probes counter.NAME and pulse.Xn (CounterProbes).
#include <memory>

#include "plc_cell/config/cell_extension.h"
#include "plc_cell/hsc/counter_probes.h"
#include "plc_cell/hsc/hsc_unit.h"

namespace plc_cell {
namespace hsc {

class CountersExtension : public CellExtension {
 public:
  std::string name() const override { return "counters"; }
  std::vector<std::string> sections() const override { return {"counters"}; }
  void install(const CellConfig& cfg, FunctionTable& t) override;
  // A counters: section in error leaves a unit with no counter (interrupts and time
  // bases still work), so the sections after it are read.
  void attach(const CellConfig& cfg, Plc& plc, ErrorList& errors) override;
  std::vector<ExtensionStatus> status(Plc& plc) const override;
  void detach(Plc& plc) override;

  // Only touch it under plc.locked(): the scan calls into it.
  HscUnit& unit() { return *unit_; }

 private:
  std::unique_ptr<HscUnit> unit_;
  std::unique_ptr<CounterProbes> probes_;
};

}  // namespace hsc
}  // namespace plc_cell
