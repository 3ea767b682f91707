#include "plc_cell/motion/axes_extension.h"

#include "plc_cell/motion/axes_online_check.h"
#include "plc_cell/motion/motion_functions.h"

namespace plc_cell {
namespace motion {

void AxesExtension::install(const CellConfig&, FunctionTable& t) { add_functions(t); }

void AxesExtension::attach(const CellConfig& cfg, Plc& plc, ErrorList& errors) {
  unit_ = std::make_unique<MotionUnit>(plc);
  probes_ = std::make_unique<AxisProbes>(unit_.get());
  online_check_ = std::make_unique<AxesOnlineCheck>(unit_.get());
  provide<MotionUnit>(unit_.get());
  provide<ProbeFacet>(probes_.get());
  provide<OnlineCheckFacet>(online_check_.get());
  const YAML::Node section = cfg.document.IsMap() ? cfg.document["axes"] : YAML::Node();
  errors.collect([&] { unit_->configure(parse_axes_config(section, cfg.file)); }, cfg.file, section);
}

// One status per configured axis: an axis whose last move ended in error (R4060+ps) warns.
std::vector<ExtensionStatus> AxesExtension::status(Plc& plc) const {
  return plc.locked([&](ScanEngine&, Memory&) {
    std::vector<ExtensionStatus> out;
    for (int n = 0; n < kAxes; ++n) {
      const AxisDef& d = unit_->config().axes[size_t(n)];
      if (!d.used) continue;
      ExtensionStatus s;
      s.name = "axis " + d.name;
      const int error = unit_->error(n);
      s.level = error ? ExtensionStatus::Level::Warn : ExtensionStatus::Level::Ok;
      s.message = error ? "error " + std::to_string(error) : unit_->busy(n) ? "moving" : "idle";
      s.values = {{"position (pulses)", std::to_string(unit_->position(n))},
                  {"frequency (Hz)", std::to_string(unit_->frequency(n))},
                  {"step", std::to_string(unit_->step(n))}};
      out.push_back(std::move(s));
    }
    return out;
  });
}

void AxesExtension::detach(Plc&) {
  withdraw<ProbeFacet>(probes_.get());
  withdraw<MotionUnit>(unit_.get());
  probes_.reset();
  unit_.reset();  // the unit unhooks itself
}

}  // namespace motion
}  // namespace plc_cell
