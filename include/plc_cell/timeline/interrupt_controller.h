#pragma once
// The priorities of the interrupt sources (manual §9.3, plus the software counters'
// HSC4I-HSC7I) and the controller that arbitrates, pre-empts and nests interrupt
// service routines (up to 5 levels). The cell's scheduler (scheduler.h) owns one: the
// counters, the timers, the input edges and the pulse axes all request through it.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "plc_cell/core/interrupt_sources.h"

namespace plc_cell {

struct Program;

namespace timeline {

// The source table and its labels are the core's (core/interrupt_sources.h).
using namespace irq;
constexpr int kMaxNesting = 5;

class InterruptController {
 public:
  // run(source, label) executes the routine; returns false on a runtime fault.
  using Runner = std::function<bool(int source, const std::string& label)>;

  InterruptController();  // table priorities, everything enabled

  // Which routines the program has (and under which label), from its labels.
  void bind(const Program& program);
  bool present(int s) const { return (present_ >> s) & 1; }
  // Bit s set: the program has a routine for source s (a scan asks for several at once).
  uint64_t present_mask() const { return present_; }
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
  uint64_t present_ = 0;
  static_assert(kSourceCount <= 64, "present_ has a bit per source");
  std::array<int, kSourceCount> priority_{};
  std::array<bool, kSourceCount> enabled_{};
  std::array<bool, kSourceCount> pending_{};
  int pending_count_ = 0;
  std::array<int, kMaxNesting> running_{};  // priorities of the running routines
  int depth_ = 0;
  bool failed_ = false;
};

}  // namespace timeline
}  // namespace plc_cell
