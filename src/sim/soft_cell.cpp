#include "plc_cell/sim/soft_cell.h"

#include "plc_cell/core/error.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/temp/hspwm.h"
#include "plc_cell/temp/temp_functions.h"
#include "plc_cell/motion/motion_unit.h"

namespace plc_cell {

FunctionTable SoftCell::functions(temp::Generation g) {
  FunctionTable t = FunctionTable::with_core_functions();
  temp::add_temperature_functions(t, g);  // FUN86 TPCTL (FBs or FB), FUN30 PID, FB: FUN72/73/85
  return t;
}

FunctionTable SoftCell::functions_for(const CellConfig& cfg, const CellFunctionInstaller& install,
                                      std::vector<std::shared_ptr<void>>* keep) {
  FunctionTable t = functions(temp::cell_generation(cfg.document, cfg.file));
  if (install) *keep = install(cfg, t);
  return t;
}

SoftCell::SoftCell(const std::string& config_path, const std::string& program_path,
                   const CellFunctionInstaller& install)
    : config_(config_path.empty() ? CellConfig() : load_cell_config(config_path)),
      plc_(functions_for(config_, install, &installed_)) {
  program_path_ = program_path.empty() ? config_.program : program_path;
  if (program_path_.empty())
    throw Error("no program: give --program or set cell.program in the cell config");
  sim_ = plc_.locked([&](ScanEngine& e, Memory& m) { return std::make_unique<SimulatedCell>(e, m); });
  apply_cell_config(config_, plc_, *sim_);
  plc_.locked([&](ScanEngine& e, Memory& m) {
    e.add_hook(sim_.get());
    temperature_ = temp::make_temperature_cell(config_.document, config_.file, m);
    if (temperature_) e.add_hook(temperature_.get());
    rtc_ = temp::make_rtc(config_.document, config_.file, m);
    e.add_hook(rtc_.get());
    pwmda_ = temp::make_pwmda_outputs(config_.document, config_.file, m);
    if (pwmda_) e.add_hook(pwmda_.get());
    return 0;
  });
  const YAML::Node& doc = config_.document;
  hsc_ = std::make_unique<hsc::HscUnit>(plc_, hsc::parse_hsc_config(doc["counters"], config_.file));
  motion_ = std::make_unique<motion::MotionUnit>(plc_);
  motion_->configure(motion::parse_axes_config(doc["axes"], config_.file));
  // Pulse and step signals on the high-speed inputs X0-X15 become exact-time edges,
  // so counters and edge interrupts see every pulse, not the scan's samples.
  plc_.locked([&](ScanEngine&, Memory&) {
    for (const auto& d : config_.sim_inputs) {
      if (d.x > 15 || d.kind == SimInputDef::Kind::Follow || hsc_->source_on(static_cast<int>(d.x))) continue;
      sim_->release(d.x);
      if (d.kind == SimInputDef::Kind::Steps) {
        for (const auto& st : d.steps) hsc_->schedule_edge(static_cast<int>(d.x), st.first * 1000, st.second);
      } else {
        hsc_->add_pulse_train(static_cast<int>(d.x), d.period_us * 1000, d.width_us * 1000, d.delay_us * 1000);
      }
    }
    return 0;
  });
  // Capture inputs beyond X15 are sampled at the scans: the simulation latches them.
  plc_.locked([&](ScanEngine&, Memory&) {
    for (uint32_t x = 16; x < hsc::kFilteredInputs; ++x)
      if (hsc_->config().capture[x]) sim_->capture(x);
    return 0;
  });
  plc_.load_program_file(program_path_);
}

SoftCell::~SoftCell() {
  installed_.clear();
  motion_.reset();
  hsc_.reset();
  plc_.locked([&](ScanEngine& e, Memory& m) {
    e.remove_hook(sim_.get());
    if (temperature_) e.remove_hook(temperature_.get());
    e.remove_hook(rtc_.get());
    if (pwmda_) e.remove_hook(pwmda_.get());
    temp::hspwm_reset(m);  // FUN139's generators belong to this PLC
    return 0;
  });
}

}  // namespace plc_cell
