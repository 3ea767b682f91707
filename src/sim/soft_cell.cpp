#include "plc_cell/sim/soft_cell.h"

#include "plc_cell/core/error.h"
#include "plc_cell/sim/apply_config.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/temp/hspwm.h"
#include "plc_cell/temp/temp_functions.h"
#include "plc_cell/motion/motion_unit.h"

namespace plc_cell {
namespace {

YAML::Node section(const CellConfig& cfg, const char* name) {
  return cfg.document.IsMap() ? cfg.document[name] : YAML::Node();
}

}  // namespace

FunctionTable SoftCell::functions(temp::Generation g) {
  FunctionTable t = FunctionTable::with_core_functions();
  temp::add_temperature_functions(t, g);  // FUN86 TPCTL (FBs or FB), FUN30 PID, FB: FUN72/73/85
  return t;
}

FunctionTable SoftCell::functions_for(const CellConfig& cfg, const CellFunctionInstaller& install,
                                      std::vector<std::shared_ptr<void>>* keep, ErrorList* errors, bool* complete) {
  temp::Generation g = temp::Generation::FBs;
  *complete &= errors->collect([&] { g = temp::cell_generation(cfg.document, cfg.file); }, cfg.file);
  FunctionTable t = functions(g);
  if (install) *complete &= errors->collect([&] { *keep = install(cfg, t); }, cfg.file);
  return t;
}

SoftCell::SoftCell(const std::string& config_path, const std::string& program_path,
                   const CellFunctionInstaller& install, const std::vector<CellSection>& sections)
    : config_(config_path.empty() ? CellConfig() : load_cell_config(config_path, &errors_)),
      plc_(functions_for(config_, install, &installed_, &errors_, &functions_complete_)) {
  try {
    build(program_path, sections);
  } catch (...) {
    release();
    throw;
  }
}

// Each subsystem reads its own section; a section in error leaves its subsystem as an
// empty one, so the sections after it are still read and reported.
void SoftCell::build(const std::string& program_path, const std::vector<CellSection>& sections) {
  const std::string& file = config_.file;
  ErrorList& errors = errors_;
  program_path_ = program_path.empty() ? config_.program : program_path;
  sim_ = plc_.locked([&](ScanEngine& e, Memory& m) { return std::make_unique<SimulatedCell>(e, m); });
  apply_cell_config(config_, plc_, *sim_);
  const YAML::Node modules = section(config_, "modules");
  plc_.locked([&](ScanEngine& e, Memory& m) {
    e.add_hook(sim_.get());
    errors.collect([&] { temperature_ = temp::make_temperature_cell(config_.document, file, m); }, file, modules);
    if (temperature_) e.add_hook(temperature_.get());
    errors.collect([&] { rtc_ = temp::make_rtc(config_.document, file, m); }, file, modules);
    if (rtc_) e.add_hook(rtc_.get());
    errors.collect([&] { pwmda_ = temp::make_pwmda_outputs(config_.document, file); }, file, modules);
    if (pwmda_) e.add_hook(pwmda_.get());
    return 0;
  });
  for (const auto& s : sections) errors.collect([&] { s.read(config_); }, file, section(config_, s.name.c_str()));
  const YAML::Node counters = section(config_, "counters");
  hsc::HscConfig hc;
  if (!errors.collect([&] { hc = hsc::parse_hsc_config(counters, file); }, file, counters)) hc = hsc::HscConfig();
  hsc_ = std::make_unique<hsc::HscUnit>(plc_, hc);
  motion_ = std::make_unique<motion::MotionUnit>(plc_);
  const YAML::Node axes = section(config_, "axes");
  errors.collect([&] { motion_->configure(motion::parse_axes_config(axes, file)); }, file, axes);
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
  // The program needs the whole instruction set: with modules.generation, fatek: or
  // modbus: in error its FUN lines would only repeat those errors.
  if (program_path_.empty()) {
    errors.throw_if_any();  // a cell: section in error may be why there is no program
    throw Error("no program: give --program or set cell.program in the cell config");
  }
  if (functions_complete_) errors.collect([&] { plc_.load_program_file(program_path_); }, program_path_);
  errors.throw_if_any();
}

void SoftCell::release() {
  installed_.clear();
  motion_.reset();
  hsc_.reset();
  plc_.locked([&](ScanEngine& e, Memory&) {
    if (sim_) e.remove_hook(sim_.get());
    if (temperature_) e.remove_hook(temperature_.get());
    if (rtc_) e.remove_hook(rtc_.get());
    if (pwmda_) e.remove_hook(pwmda_.get());
    temp::hspwm_reset(e);  // FUN139's generators belong to this PLC: off with its cell
    return 0;
  });
}

SoftCell::~SoftCell() { release(); }

}  // namespace plc_cell
