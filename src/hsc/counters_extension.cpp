#include "plc_cell/hsc/counters_extension.h"

#include "plc_cell/hsc/hsc_functions.h"

namespace plc_cell {
namespace hsc {

void CountersExtension::install(const CellConfig&, FunctionTable& t) { add_functions(t); }

void CountersExtension::attach(const CellConfig& cfg, Plc& plc, ErrorList& errors) {
  const YAML::Node section = cfg.document.IsMap() ? cfg.document["counters"] : YAML::Node();
  HscConfig hc;
  if (!errors.collect([&] { hc = parse_hsc_config(section, cfg.file); }, cfg.file, section)) hc = HscConfig();
  unit_ = std::make_unique<HscUnit>(plc, hc);
  probes_ = std::make_unique<CounterProbes>(unit_.get());
  provide<HscUnit>(unit_.get());
  provide<ProbeFacet>(probes_.get());
}

std::vector<ExtensionStatus> CountersExtension::status(Plc& plc) const {
  ExtensionStatus s;
  s.name = "counters";
  int used = 0;
  plc.locked([&](ScanEngine&, Memory&) {
    for (int n = 0; n < 8; ++n) {
      const CounterDef& d = unit_->config().counters[size_t(n)];
      if (!d.used) continue;
      ++used;
      s.values.push_back({d.name, std::to_string(unit_->count(n))});
    }
    return 0;
  });
  s.message = std::to_string(used) + (used == 1 ? " counter" : " counters") + " configured";
  return {s};
}

void CountersExtension::detach(Plc&) {
  withdraw<ProbeFacet>(probes_.get());
  withdraw<HscUnit>(unit_.get());
  probes_.reset();
  unit_.reset();  // the unit unhooks itself
}

}  // namespace hsc
}  // namespace plc_cell
