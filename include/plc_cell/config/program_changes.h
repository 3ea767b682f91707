#pragma once
// A change of a running cell's program, as every entry point asks for it (plc_node's
// ~load_program, the monitor's Edit tab, `plc_cell run --watch-program`): one interface, one
// implementation (online/change_service.h), so the three parse, check, gate, swap and log a
// change the same way (docs/online-change.md). The monitor sees only this interface.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace plc_cell {

// Where a change came from: the audit trail's `source`.
enum class ChangeSource { Service, Page, File };
const char* source_text(ChangeSource s);  // "service", "page", "file"

struct ChangeRequest {
  std::string text;  // the new program's IL
  ChangeSource source = ChangeSource::Service;
  // Apply although the gate failed: only with a reason, and logged as forced. What a
  // change may not do in RUN is refused all the same.
  bool force = false;
  std::string reason;
};

// One error of the new program where the parser gives it.
struct ProgramError {
  int line = 0, column = 0;
  std::string message;
};

// The gate's verdict on one program text (plc_cell gate's report).
struct GateResult {
  bool configured = false;  // the cell YAML has a gate: section
  bool passed = true;       // no gate passes
  std::string summary;      // one line: "4 case(s) passed, explore: no property violated"
  nlohmann::json report;    // plc_cell gate --json's report as it gave it (null: no gate)
  double seconds = 0;       // wall time the gate took
  std::string hash;         // of the program text it ran on
  std::string since;        // with gate.mutate: of the running program it was compared with
};

struct ChangeOutcome {
  std::string result;  // "applied", "forced", "refused", or "checked" (check() only)
  std::string why;     // a refusal's reason, one line
  std::vector<ProgramError> errors;   // the new program's parse errors
  std::vector<std::string> refusals;  // what the change may not do in RUN
  GateResult gate;
  std::string old_hash, new_hash;
  std::string diff;         // unified diff of the IL, old to new
  double swap_ms = 0;       // the PLC lock held for the swap
  uint32_t instructions = 0;
  bool undo = false;  // the change was an Undo
};

class ProgramChanges {
 public:
  virtual ~ProgramChanges() = default;
  // The running program's text, its hash and its file.
  virtual std::string text() const = 0;
  virtual std::string hash() const = 0;
  virtual std::string file() const = 0;
  virtual bool has_gate() const = 0;
  // Parsed and checked against the running program; nothing runs, nothing is logged.
  virtual ChangeOutcome check(const std::string& text) = 0;
  // The gate on text, in a process of its own, bounded; the running scan goes on.
  virtual GateResult test(const std::string& text) = 0;
  // The one path: parse, check, compile beside, gate, swap at a scan boundary, log.
  virtual ChangeOutcome apply(const ChangeRequest& request) = 0;
  // Back to the program the last applied change replaced, by apply's path.
  virtual ChangeOutcome undo(ChangeSource source) = 0;
  // The audit trail, oldest first (at most the last `last` entries).
  virtual nlohmann::json log(size_t last) const = 0;
};

nlohmann::json to_json(const GateResult& g);
nlohmann::json to_json(const ChangeOutcome& o);

}  // namespace plc_cell
