#pragma once
// The 49 interrupt sources of the FBs-PLC (manual §9.3) plus the software
// counters' HSC4I-HSC7I, their priorities, and the controller that arbitrates,
// pre-empts and nests interrupt service routines (up to 5 levels).
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace plc_cell {

struct Program;

namespace hsc {

// Source ids, in priority order for the 49 of the table.
enum Source : int {
  kHstaI = 0,
  kTimeBase0 = 1,   // 1MSI ... 100MSI = 1..8
  kHsc0I = 9,       // HSC0I/HST0I ... HSC3I/HST3I = 9..12
  kPso0I = 13,      // PSO0I ... PSO3I = 13..16 (the pulse-output axes raise them)
  kX0Up = 17,       // X0+I, X0-I, X1+I ... X15-I = 17..48
  kHsc4I = 49,      // HSC4I ... HSC7I = 49..52 (priority of their input: AMBIG-3)
  kSourceCount = 53,
};
constexpr int kMaxNesting = 5;
constexpr uint32_t kTimeBaseMs[8] = {1, 2, 3, 4, 5, 10, 50, 100};

inline int x_edge_source(int x, bool falling) { return kX0Up + 2 * x + (falling ? 1 : 0); }

// Labels accepted for a source: the new name first, then the old one(s).
std::vector<std::string> source_labels(int source);
// Source of a label (new or old name, upper case); -1 if it is not reserved.
int source_of_label(const std::string& label);

class InterruptController {
 public:
  // run(source, label) executes the routine; returns false on a runtime fault.
  using Runner = std::function<bool(int source, const std::string& label)>;

  InterruptController();  // table priorities, everything enabled

  // Which routines the program has (and under which label), from its labels.
  void bind(const Program& program);
  bool present(int s) const { return !label_[s].empty(); }
  const std::string& label(int s) const { return label_[s]; }

  void set_priority(int s, int p) { priority_[s] = p; }
  int priority(int s) const { return priority_[s]; }
  void set_enabled(int s, bool e) { enabled_[s] = e; }
  bool enabled(int s) const { return enabled_[s]; }

  // A request: ignored if the source has no routine or is disabled. Runs at once
  // what may run now (higher priority than every running routine, depth < 5);
  // the rest waits in pending until it is the highest.
  void raise(int s, const Runner& run);
  // Marks a request pending without running anything (simultaneous events are all
  // requested first, then dispatch() runs the highest).
  void request(int s);
  // Runs what may run; called after a routine returns and by raise.
  void dispatch(const Runner& run);
  bool idle() const { return depth_ == 0 && pending_count_ == 0; }
  int depth() const { return depth_; }
  bool failed() const { return failed_; }
  void reset();

 private:
  std::array<std::string, kSourceCount> label_{};
  std::array<int, kSourceCount> priority_{};
  std::array<bool, kSourceCount> enabled_{};
  std::array<bool, kSourceCount> pending_{};
  int pending_count_ = 0;
  std::array<int, kMaxNesting> running_{};  // priorities of the running routines
  int depth_ = 0;
  bool failed_ = false;
};

}  // namespace hsc
}  // namespace plc_cell
