#include "plc_cell/temp/modules_extension.h"

#include "plc_cell/temp/hspwm.h"
#include "plc_cell/temp/temp_functions.h"
#include "plc_cell/temp/temperature_config.h"

namespace plc_cell {
namespace temp {

void ModulesExtension::install(const CellConfig& cfg, FunctionTable& t) {
  add_temperature_functions(t, cell_generation(cfg.document, cfg.file));
}

void ModulesExtension::attach(const CellConfig& cfg, Plc& plc, ErrorList& errors) {
  const std::string& file = cfg.file;
  const YAML::Node modules = cfg.document.IsMap() ? cfg.document["modules"] : YAML::Node();
  plc.locked([&](ScanEngine& e, Memory& m) {
    errors.collect([&] { temperature_ = make_temperature_cell(cfg.document, file, m); }, file, modules);
    if (temperature_) e.add_hook(temperature_.get());
    errors.collect([&] { rtc_ = make_rtc(cfg.document, file, m, cfg.clock); }, file, modules);
    if (rtc_) e.add_hook(rtc_.get());
    errors.collect([&] { pwmda_ = make_pwmda_outputs(cfg.document, file); }, file, modules);
    if (pwmda_) e.add_hook(pwmda_.get());
    return 0;
  });
  probes_ = std::make_unique<ModuleProbes>(temperature_.get());
  provide<ProbeFacet>(probes_.get());
  if (temperature_) provide<TemperatureCell>(temperature_.get());
  if (rtc_) provide<Rtc>(rtc_.get());
  if (pwmda_) provide<PwmdaOutputs>(pwmda_.get());
}

void ModulesExtension::detach(Plc& plc) {
  plc.locked([&](ScanEngine& e, Memory&) {
    if (temperature_) e.remove_hook(temperature_.get());
    if (rtc_) e.remove_hook(rtc_.get());
    if (pwmda_) e.remove_hook(pwmda_.get());
    hspwm_reset(e);  // FUN139's generators belong to this PLC: off with its cell
    return 0;
  });
  withdraw<ProbeFacet>(probes_.get());
  withdraw<TemperatureCell>(temperature_.get());
  withdraw<Rtc>(rtc_.get());
  withdraw<PwmdaOutputs>(pwmda_.get());
}

}  // namespace temp
}  // namespace plc_cell
