#pragma once
// A soft PLC with its cell config, its subsystems and simulated inputs: how every cell is
// assembled (the Cell of runtime/cell.h builds one for check, sim, run and plc_node). The
// subsystems are cell extensions (config/cell_extension.h), each taken through the same
// steps: the counters, the axes and the temperature modules always, and the extensions
// the caller adds (FUN150/151 and their ports, the servers' settings), then those registered
// (config/extension_registry.h). Building starts
// nothing: no thread, no port, no server (the extensions decide about their own).
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/cell_extension.h"
#include "plc_cell/config/error_list.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/sim/simulated_cell.h"

namespace plc_cell {

namespace hsc {
class CountersExtension;
}

using CellExtensions = std::vector<std::unique_ptr<CellExtension>>;

class SoftCell {
 public:
  // config_path may be empty (no signals, no simulation); program_path overrides the
  // config's cell.program. Every section of the config is read even when an earlier one
  // failed, then the program (when every extension installed its FUNs, so that the
  // program's FUN lines would not only repeat those errors); one SourceError lists every
  // error found, each with file:line:column. A config or program that cannot be opened,
  // or "no program", throws at once. more: extensions after the built-in ones. clock: how
  // the cell's time runs (config/cell_clock.h; virtual unless said otherwise). The file's
  // plc.engine: lockstep needs a twin, a second SoftCell: run_in_lockstep
  // (sim/lockstep_cells.h), which the Cell of runtime/cell.h calls; until then, native.
  SoftCell(const std::string& config_path, const std::string& program_path, CellExtensions more = {},
           CellClock clock = {});
  // The instruction set of a cell without a file: the core's plus every built-in
  // extension's FUNs (what a bare Plc needs to run a cell's program).
  static FunctionTable functions();
  // The sections the built-in extensions and `more` claim: with the core's, the
  // top-level keys of a cell file.
  static std::set<std::string> sections(const CellExtensions& more = {});
  ~SoftCell();

  Plc& plc() { return plc_; }
  // Only touch it under plc().locked(): the scan calls into it.
  SimulatedCell& simulation() { return *sim_; }
  const CellConfig& config() const { return config_; }
  // Every extension, built-in first, in the order they were attached.
  const CellExtensions& extensions() const { return extensions_; }
  // The first facet of type F an extension declared (config/cell_extension.h), or nullptr:
  // get<ProbeFacet>() for a probe family, get<hsc::HscUnit>() in a subsystem's own code
  // and tests. Only touch a subsystem object under plc().locked(): the scan calls into it.
  template <class F>
  F* get() const {
    for (const auto& x : extensions_)
      if (F* f = x->template get<F>()) return f;
    return nullptr;
  }
  const std::string& program_path() const { return program_path_; }
  // What the program's FUNs will refuse at run time although the PLC accepts them
  // (core/operand_rules.h): a warning with file:line:column each, for `check` and `sim`.
  std::vector<Diagnostic> warnings();

 private:
  static CellExtensions with_builtins(CellExtensions more);
  CellConfig load(const std::string& path, const CellClock& clock);
  FunctionTable install();
  void build(const std::string& program_path);
  void release();  // extensions off the engine in reverse order (port owners first)

  ErrorList errors_;                // while building; before config_, which fills it
  bool functions_complete_ = true;  // every extension installed its FUNs
  CellExtensions extensions_;       // before config_ (their sections) and plc_ (their FUNs)
  CellConfig config_;
  hsc::CountersExtension* counters_ = nullptr;  // the exact-time edges of the simulated inputs
  std::string program_path_;
  Plc plc_;
  std::unique_ptr<SimulatedCell> sim_;  // its hook runs before the extensions': they see the simulated inputs
};

}  // namespace plc_cell
