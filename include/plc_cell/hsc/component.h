#pragma once
// One part of the counters' unit (a counter, a timer, an input's pulse measurement, the
// edge interrupts): the unit composes its parts and calls each, in one fixed order, at
// the points of the scheduler's loop and of the scan. Only configured parts are in the
// list, so an unused counter or input costs nothing per scan.
//
// The order is the unit's (hsc_unit.cpp): counters and timers by number, then the
// time-base and HSTA interrupts, the edge interrupts and the pulse measurements, so that
// interrupt requests and match observers see the same sequence at one instant.
#include <array>
#include <cstdint>
#include <type_traits>

#include "plc_cell/timeline/event_source.h"

namespace plc_cell {
namespace hsc {

// The levels of X0-X15 after the filter, as the explicit edges left them.
using InputLevels = std::array<bool, 16>;

class Component {
 public:
  static constexpr uint64_t kNever = timeline::EventSource::kNever;
  virtual ~Component() = default;

  // ---- the scheduler's loop (timeline::EventSource) ----
  virtual void start(uint64_t /*t_ns*/) {}   // RUN from t
  virtual void settle() {}                   // an analytic source may have jumped at now
  virtual uint64_t next_event_ns() { return kNever; }  // kept for at()
  virtual void advance_to(uint64_t /*t_ns*/) {}        // from now to t, events excluded
  virtual void at(uint64_t /*t_ns*/) {}                // its events found for t
  // Explicit edges of X0-X15 acting together at t: the levels before and after.
  virtual void input_edges(uint64_t /*t_ns*/, const InputLevels& /*before*/, const InputLevels& /*after*/) {}

  // ---- the scan ----
  virtual void before_inputs() {}
  virtual void after_program() {}

  // The scheduler's optional steps a part of type T has code for (as
  // EventSource::steps_of): the unit calls settle and advance_to only on those parts.
  template <class T>
  static constexpr unsigned steps_of() {
    using timeline::EventSource;
    if constexpr (!std::is_final<T>::value) {
      return EventSource::kEveryStep;
    } else {
      return (std::is_same<decltype(&T::settle), void (Component::*)()>::value ? 0u : EventSource::kSettles) |
             (std::is_same<decltype(&T::advance_to), void (Component::*)(uint64_t)>::value ? 0u
                                                                                           : EventSource::kAdvances);
    }
  }
};

}  // namespace hsc
}  // namespace plc_cell
