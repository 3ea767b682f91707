#include "plc_cell/sim/soft_cell.h"

#include "plc_cell/config/extension_registry.h"
#include "plc_cell/config/gate_config.h"
#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/unreadable.h"
#include "plc_cell/hsc/counters_extension.h"
#include "plc_cell/motion/axes_extension.h"
#include "plc_cell/sim/apply_config.h"
#include "plc_cell/temp/modules_extension.h"

namespace plc_cell {
namespace {

YAML::Node first_section(const CellConfig& cfg, const CellExtension& x) {
  const auto s = x.sections();
  return cfg.document.IsMap() && !s.empty() ? cfg.document[s.front()] : YAML::Node();
}

}  // namespace

// The instruction set of a cell's program, in one place: the core's, then each built-in
// subsystem's (the same lists their extensions install).
FunctionTable SoftCell::functions() {
  FunctionTable t = FunctionTable::with_core_functions();
  const CellConfig none;  // every extension's defaults (the FBs generation's FUN86)
  for (auto& x : with_builtins({})) x->install(none, t);
  return t;
}

namespace {
void add_claims(const CellExtensions& xs, std::set<std::string>* out) {
  for (const auto& x : xs)
    for (const auto& s : x->sections()) out->insert(s);
}
}  // namespace

std::set<std::string> SoftCell::sections(const CellExtensions& more) {
  std::set<std::string> out;
  add_claims(with_builtins({}), &out);
  add_claims(more, &out);
  return out;
}

// The built-in subsystems come first, in the order they attach: the temperature modules,
// the counters (whose edge sources the axes' pins and encoders are), the axes; then the
// gate: section, which every cell file may have (docs/online-change.md).
CellExtensions SoftCell::with_builtins(CellExtensions more) {
  CellExtensions all;
  all.push_back(std::make_unique<temp::ModulesExtension>());
  all.push_back(std::make_unique<hsc::CountersExtension>());
  all.push_back(std::make_unique<motion::AxesExtension>());
  all.push_back(gate_section());
  for (auto& x : more) all.push_back(std::move(x));
  for (auto& x : registered_extensions()) all.push_back(std::move(x));
  return all;
}

// The file's sections are the core's and those the extensions claim.
CellConfig SoftCell::load(const std::string& path, const CellClock& clock) {
  CellConfig c;
  if (!path.empty()) {
    std::set<std::string> sections;
    add_claims(extensions_, &sections);
    c = load_cell_config(path, &errors_, sections);
  }
  c.clock = clock;
  return c;
}

FunctionTable SoftCell::install() {
  FunctionTable t = FunctionTable::with_core_functions();
  for (auto& x : extensions_)
    functions_complete_ &= errors_.collect([&] { x->install(config_, t); }, config_.file, first_section(config_, *x));
  return t;
}

SoftCell::SoftCell(const std::string& config_path, const std::string& program_path, CellExtensions more,
                   CellClock clock)
    : extensions_(with_builtins(std::move(more))),
      config_(load(config_path, clock)),
      counters_(static_cast<hsc::CountersExtension*>(extensions_[1].get())),
      plc_(install()) {
  try {
    build(program_path);
  } catch (...) {
    release();
    throw;
  }
}

// Each extension reads its own sections; a section in error leaves its subsystem as an
// empty one, so the sections after it are still read and reported.
void SoftCell::build(const std::string& program_path) {
  ErrorList& errors = errors_;
  program_path_ = program_path.empty() ? config_.program : program_path;
  sim_ = plc_.locked([&](ScanEngine& e, Memory& m) { return std::make_unique<SimulatedCell>(e, m); });
  apply_cell_config(config_, plc_, *sim_);
  plc_.locked([&](ScanEngine& e, Memory&) {
    e.add_hook(sim_.get());
    return 0;
  });
  for (auto& x : extensions_) x->attach(config_, plc_, errors);
  hsc::HscUnit& hsc = counters_->unit();
  // Pulse and step signals on the high-speed inputs X0-X15 become exact-time edges,
  // so counters and edge interrupts see every pulse, not the scan's samples.
  plc_.locked([&](ScanEngine&, Memory&) {
    sim_->exact_edges(&hsc);
    for (const auto& d : config_.sim_inputs) {
      if (d.x > 15 || d.kind == SimInputDef::Kind::Follow || hsc.source_on(static_cast<int>(d.x))) continue;
      sim_->drop(d.x);
      if (d.kind == SimInputDef::Kind::Steps) {
        for (const auto& st : d.steps) hsc.schedule_edge(static_cast<int>(d.x), st.first * 1000, st.second);
      } else {
        hsc.add_pulse_train(static_cast<int>(d.x), d.period_us * 1000, d.width_us * 1000, d.delay_us * 1000);
      }
    }
    return 0;
  });
  // Capture inputs beyond X15 are sampled at the scans: the simulation latches them.
  plc_.locked([&](ScanEngine&, Memory&) {
    for (uint32_t x = 16; x < hsc::kFilteredInputs; ++x)
      if (hsc.config().capture[x]) sim_->capture(x);
    return 0;
  });
  if (program_path_.empty()) {
    errors.throw_if_any();  // a cell: section in error may be why there is no program
    throw Error("no program: give --program or set cell.program in the cell config");
  }
  // A program the cell YAML names but that cannot be read: the error is at that line,
  // with where the path led (relative paths are from the YAML's folder).
  const YAML::Node& doc = config_.document;
  bool readable = true;
  if (program_path.empty() && doc.IsMap() && doc["cell"].IsMap() && doc["cell"]["program"]) {
    const std::string why = why_unreadable(program_path_);
    readable = why.empty();
    if (!readable) {
      errors.collect([&] {
        YamlReader(config_.file).fail(doc["cell"]["program"], "cell.program", "cannot open the program file: " + why);
      }, config_.file);
    }
  }
  if (functions_complete_ && readable)
    errors.collect([&] { plc_.load_program_file(program_path_); }, program_path_);
  errors.throw_if_any();
}

std::vector<Diagnostic> SoftCell::warnings() {
  return plc_.locked([&](ScanEngine& e, Memory&) { return operand_warnings(e.program(), plc_.functions()); });
}

void SoftCell::release() {
  for (auto it = extensions_.rbegin(); it != extensions_.rend(); ++it) (*it)->detach(plc_);
  plc_.locked([&](ScanEngine& e, Memory&) {
    if (sim_) e.remove_hook(sim_.get());
    return 0;
  });
}

SoftCell::~SoftCell() { release(); }

}  // namespace plc_cell
