#pragma once
// The cell's virtual time between two scans: one event loop for every subsystem with
// events of its own, and the interrupt system that runs routines at those instants.
//
// Between scans the scheduler moves the clock from event to event: it asks each source
// for its next instant, brings all of them to the earliest, lets each act there, then
// dispatches the interrupt requests of that instant together (arbitration, pre-emption
// and nesting by priority, manual §9.3). Sources find their instants in O(1), so the
// cost of a scan does not depend on signal frequencies (docs/counters-and-interrupts.md).
//
// One per scan engine, in the engine's extension slots: the first subsystem that needs it
// makes it (Scheduler::of), so counters and axes share one clock and one interrupt system
// whichever of them a cell has.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "plc_cell/core/scan_engine.h"
#include "plc_cell/timeline/event_source.h"
#include "plc_cell/timeline/interrupt_controller.h"

namespace plc_cell {
namespace timeline {

class Scheduler final : public ScanHook {
 public:
  Scheduler() = default;  // made by of(), which binds it to its engine
  Scheduler(const Scheduler&) = delete;
  Scheduler& operator=(const Scheduler&) = delete;

  // The engine's scheduler, made and hooked on first use (engine lock held). Its hook
  // comes before those of the subsystems that ask for it, so each scan first brings the
  // cell's clock to the scan's instant.
  static Scheduler& of(ScanEngine& engine);
  // The engine's scheduler if some subsystem made one, else null (FUN handlers).
  static Scheduler* find(ScanEngine* engine);

  // Sources act at an instant in the order they were added.
  template <class T>
  void add_source(T* s) {
    add_source(s, EventSource::steps_of<T>());
  }
  void add_source(EventSource* s, unsigned steps);
  void remove_source(EventSource* s);

  // Runs the event loop up to to_ns (inclusive). Does nothing unless running.
  void advance(uint64_t to_ns);
  uint64_t now_ns() const { return now_ns_; }
  // In RUN since the last start: the clock moves and routines may run.
  bool running() const { return running_; }

  InterruptController& interrupts() { return irq_; }
  // An interrupt request. Inside the loop (a source acting at an instant) it waits until
  // every source has acted there; elsewhere (an instruction in the scan, a routine) the
  // routine runs now if its priority allows.
  void raise(int source);

  // Every routine entry at its instant (`plc_cell sim --trace`, tests).
  using IsrObserver = std::function<void(uint64_t t_ns, int source)>;
  void on_isr(IsrObserver f) { isr_obs_.push_back(std::move(f)); }

  void before_inputs(uint64_t now_us) override;
  void on_stop() override;

 private:
  void start(uint64_t t_ns);
  void dispatch();
  bool run_isr(int source);

  ScanEngine* engine_ = nullptr;
  InterruptController irq_;
  std::vector<EventSource*> sources_;
  // The sources with code for settle / advance_to (EventSource::steps_of), in order.
  std::vector<EventSource*> settling_, advancing_;
  std::vector<int> requested_;  // raised at the present instant, not yet dispatched
  std::vector<IsrObserver> isr_obs_;
  const void* bound_code_ = nullptr;
  size_t bound_size_ = 0;
  uint64_t now_ns_ = 0;
  bool running_ = false;
  bool in_instant_ = false;
};

}  // namespace timeline
}  // namespace plc_cell
