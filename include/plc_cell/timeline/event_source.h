#pragma once
// A subsystem with events between two scans (the counters' CV=PV matches, timer expiries
// and input edges; the pulse axes' step ends): the scheduler (scheduler.h) asks each for
// its next instant, moves the cell's clock to the earliest, and lets each act there.
#include <cstdint>
#include <type_traits>

namespace plc_cell {
namespace timeline {

class EventSource {
 public:
  static constexpr uint64_t kNever = UINT64_MAX;
  virtual ~EventSource() = default;

  // RUN begins at t: state that lives for one run starts over.
  virtual void start(uint64_t /*t_ns*/) {}
  // RUN ends (STOP or a fault) while the scheduler was running.
  virtual void stop() {}
  // Before the next instant is chosen: catch up with changes made since the last one
  // (a pulse source re-planned by an axis); requests made here are dispatched at once.
  virtual void settle() {}
  // The earliest instant at which this source acts (kNever: none). The scheduler
  // takes the minimum over all sources, so a source may keep what it found for at().
  virtual uint64_t next_event_ns() = 0;
  // Every source is brought to t before any acts at t, so that each sees the others'
  // state of that instant.
  virtual void advance_to(uint64_t /*t_ns*/) {}
  // At the chosen instant t, in registration order: act if something of this source
  // falls there. Interrupt requests made here are dispatched together after all acted.
  virtual void at(uint64_t t_ns) = 0;

  // Which of the optional steps a source of type T has code for, as ScanHook::phases_of
  // reads a hook's phases: a step T does not declare is EventSource's empty one, and the
  // scheduler does not call it at every scan. Only a final T is read this way.
  enum Step : unsigned { kSettles = 1u, kAdvances = 2u, kEveryStep = 3u };
  template <class T>
  static constexpr unsigned steps_of() {
    if constexpr (!std::is_final<T>::value) {
      return kEveryStep;
    } else {
      return (std::is_same<decltype(&T::settle), void (EventSource::*)()>::value ? 0u : kSettles) |
             (std::is_same<decltype(&T::advance_to), void (EventSource::*)(uint64_t)>::value ? 0u : kAdvances);
    }
  }
};

}  // namespace timeline
}  // namespace plc_cell
