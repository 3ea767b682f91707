#pragma once
// Leaving a PLC as a case found it (docs/testing-on-hardware.md, "Restore"): what the case
// will touch is read before it starts; afterwards, whatever happened, every point it
// touched is put back (a point found forced is forced again at its state, one the case
// forced is released, every value written back), retried while the link is down, and what
// could not be put back is said point by point. A journal on disk holds the same, so that
// a run killed outright is restored by the next run against the same PLC.
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "plc_cell/scenario/linked_plc.h"
#include "plc_cell/scenario/wall_clock.h"

namespace plc_cell {
namespace scenario {

struct FoundPoint {
  TouchedPoint point;
  uint32_t value = 0;
  std::optional<bool> forced;  // nullopt: the link cannot tell (then taken as not forced)
};

// Reads points as they are now: their values, and which are forced where the link tells.
std::vector<FoundPoint> read_found(LinkedPlc& plc, const std::vector<TouchedPoint>& points);

struct RestoreOptions {
  // How long to keep trying while the link is down.
  std::chrono::milliseconds retry_for{30000};
  // Waits up to d before the next attempt; true when the user gives up (a second Ctrl-C).
  std::function<bool(std::chrono::milliseconds)> wait;
  // Told once when the link is down and the restore waits for it.
  std::function<void(const std::string& why)> waiting;
};

struct RestoreResult {
  std::vector<std::string> restored;      // "part_present (X3): released, OFF as found"
  std::vector<std::string> not_restored;  // "part_present (X3): still forced ON, found not forced: <why>"
  bool complete() const { return not_restored.empty(); }
};

// Puts back each point of found whose address is in touched.
RestoreResult restore_points(LinkedPlc& plc, const std::vector<FoundPoint>& found, const std::vector<Address>& touched,
                             const RestoreOptions& opt);

// The journal of one case on disk: written before the case's first write, a line per point
// as it is first touched (each synced), removed once the case is restored.
class RestoreJournal {
 public:
  explicit RestoreJournal(std::string path) : path_(std::move(path)) {}
  ~RestoreJournal();
  RestoreJournal(const RestoreJournal&) = delete;
  RestoreJournal& operator=(const RestoreJournal&) = delete;
  const std::string& path() const { return path_; }
  // Throws Error naming the file when it cannot be written.
  void begin(const std::string& target, const std::string& case_name, const std::vector<FoundPoint>& found);
  void touched(const Address& a);
  void remove();

  struct Left {
    std::string target, case_name;
    std::vector<FoundPoint> found;
    std::vector<Address> touched;
  };
  // What a run that did not finish left at path; nullopt when there is no journal. Throws
  // Error naming the file and line of a journal it cannot read.
  static std::optional<Left> load(const std::string& path);

 private:
  void append(const std::string& line);
  std::string path_;
  int fd_ = -1;
};

}  // namespace scenario
}  // namespace plc_cell
