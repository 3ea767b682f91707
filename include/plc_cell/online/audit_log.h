#pragma once
// The audit trail of a cell's program changes (docs/online-change.md, "Audit trail"): one
// JSON object per line appended to <program>.changes.jsonl beside the program, for every
// change attempted (applied, forced or refused), and every program that ran kept by its
// hash in <program>.versions/ so that Undo works after a restart too.
#include <mutex>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "plc_cell/config/program_changes.h"

namespace plc_cell {
namespace online {

class AuditLog {
 public:
  explicit AuditLog(const std::string& program_path);

  const std::string& path() const { return path_; }
  // Appends one entry (the outcome, its source, reason and the instant); throws
  // plc_cell::Error when the log cannot be written: a change that cannot be logged is not made.
  void append(const ChangeOutcome& o, ChangeSource source, const std::string& reason);
  // Every entry, oldest first; at most the last `last`. A line that is not JSON (a torn
  // write) is shown as {"unreadable": line}, never dropped in silence.
  nlohmann::json entries(size_t last) const;
  // Keeps text under its hash; throws plc_cell::Error when it cannot.
  void keep_version(const std::string& hash, const std::string& text) const;
  std::optional<std::string> version(const std::string& hash) const;
  // What Undo goes back to, as its hash: the program the last applied (or forced) change
  // not yet undone replaced. Each Undo takes one change back, so two go back two changes.
  std::optional<std::string> undo_target() const;

 private:
  std::string path_, versions_;
  mutable std::mutex mu_;
};

// The current instant as UTC ISO 8601 with milliseconds: "2026-03-01T10:42:07.125Z".
std::string utc_now();

}  // namespace online
}  // namespace plc_cell
