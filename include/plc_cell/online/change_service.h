#pragma once
// The one path of a program change in RUN (docs/online-change.md), for plc_node's
// ~load_program, the monitor's Edit tab and `plc_cell run --watch-program`: the new text is
// parsed, checked against the running program and compiled beside it; the cell's gate runs
// on it in a process of its own; it is swapped in at a scan boundary keeping memory, timers,
// counters, forces and the retentive image; every attempt goes to the audit trail.
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "plc_cell/config/cell_extension.h"
#include "plc_cell/config/program_changes.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/online/audit_log.h"
#include "plc_cell/config/gate_config.h"

namespace plc_cell {
namespace online {

struct ChangeSetup {
  std::string cell_file;     // the cell YAML the gate's process reads ("" = no cell: no gate)
  std::string program_path;  // the running program's file
  GateConfig gate;
  const std::vector<std::unique_ptr<CellExtension>>* extensions = nullptr;  // their OnlineCheckFacets
  std::string tool;  // the plc_cell tool the gate runs ("" = tool_path())
};

class ChangeService : public ProgramChanges {
 public:
  ChangeService(Plc& plc, ChangeSetup setup);

  std::string text() const override;
  std::string hash() const override;
  // The running program's text and hash, read together.
  std::pair<std::string, std::string> running_text() const;
  std::string file() const override { return setup_.program_path; }
  bool has_gate() const override { return setup_.gate.line != 0; }
  ChangeOutcome check(const std::string& text) override;
  GateResult test(const std::string& text) override;
  ChangeOutcome apply(const ChangeRequest& request) override;
  ChangeOutcome undo(ChangeSource source) override;
  nlohmann::json log(size_t last) const override { return log_.entries(last); }

 private:
  // check() once the parse is known; fills errors or *program.
  ChangeOutcome examine(const std::string& text, Program* program, bool* parsed);
  std::vector<std::string> refusals_locked(const ScanEngine& e, const Program& next) const;
  GateResult gate_for(const std::string& text, const std::string& hash);
  ChangeOutcome apply_locked(const ChangeRequest& request, bool undo);
  // Logs o (the reason given with it) and returns it.
  ChangeOutcome logged(ChangeOutcome o, const ChangeRequest& r);
  void rewrite_program_file(const std::string& text) const;
  std::string compile_beside(const Program& program) const;  // "" or why it cannot run

  Plc& plc_;
  ChangeSetup setup_;
  AuditLog log_;
  std::mutex apply_mu_;    // one change at a time
  mutable std::mutex mu_;  // the running program's text and hash
  std::string text_, hash_;
  std::mutex gate_mu_;
  GateResult last_gate_;  // the last gate that ran, by its program's hash
};

}  // namespace online
}  // namespace plc_cell
