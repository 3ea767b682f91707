#pragma once
// The analog and temperature subsystem as a cell extension: the `modules:` section (its
// generation decides FUN86's form and the FB-only FUNs), the temperature modules with
// their thermal plants, the RTC board and the PWM-DA outputs.
// Facets: the TemperatureCell, Rtc and PwmdaOutputs the cell has, and the probes
// temperature.CHANNEL and analog.CHANNEL (ModuleProbes).
#include <memory>

#include "plc_cell/config/cell_extension.h"
#include "plc_cell/temp/module_probes.h"
#include "plc_cell/temp/pwmda.h"
#include "plc_cell/temp/rtc.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace temp {

class ModulesExtension : public CellExtension {
 public:
  std::string name() const override { return "modules"; }
  std::vector<std::string> sections() const override { return {"modules"}; }
  // FUN86 TPCTL (FBs or FB), FUN30 PID, FUN32/33, FUN139, and on FB FUN72/73/85.
  void install(const CellConfig& cfg, FunctionTable& t) override;
  // Each of the three parts is read even when another is in error.
  void attach(const CellConfig& cfg, Plc& plc, ErrorList& errors) override;
  void detach(Plc& plc) override;

  // nullptr when the cell has none. Only touch them under plc.locked().
  TemperatureCell* temperature() { return temperature_.get(); }
  Rtc* rtc() { return rtc_.get(); }
  PwmdaOutputs* pwmda() { return pwmda_.get(); }

 private:
  std::unique_ptr<TemperatureCell> temperature_;
  std::unique_ptr<Rtc> rtc_;
  std::unique_ptr<PwmdaOutputs> pwmda_;
  std::unique_ptr<ModuleProbes> probes_;
};

}  // namespace temp
}  // namespace plc_cell
