#pragma once
// The per-PLC state that FUN handlers reach: the counter unit, the axes, the temperature
// modules, FUN139's generators. A handler sees its PLC only through ExecContext, so each
// subsystem's object sits in a slot of its scan engine, one slot per type, found by index
// in O(1): no walk over the scan hooks, no global map keyed by the PLC's memory and no lock.
// Slots are read and written under the PLC lock, like everything else of the engine.
#include <cstddef>
#include <memory>
#include <vector>

namespace plc_cell {

class ExtensionSlots {
 public:
  // The object attached for T, or null.
  template <class T>
  T* get() const {
    const size_t i = index<T>();
    return i < slots_.size() ? static_cast<T*>(slots_[i].ptr) : nullptr;
  }
  // Attaches an object its owner keeps (and detaches before it goes).
  template <class T>
  void attach(T* p) {
    slot(index<T>()) = Slot{p, nullptr};
  }
  template <class T>
  void detach(const T* p) {
    const size_t i = index<T>();
    if (i < slots_.size() && slots_[i].ptr == p) slots_[i] = Slot{};
  }
  // State that belongs to the PLC itself (FUN139's generators): made on first use and
  // kept until the engine goes or reset<T>() drops it.
  template <class T>
  T& owned() {
    Slot& s = slot(index<T>());
    if (!s.ptr) {
      auto p = std::make_shared<T>();
      s = Slot{p.get(), p};
    }
    return *static_cast<T*>(s.ptr);
  }
  template <class T>
  void reset() {
    const size_t i = index<T>();
    if (i < slots_.size() && slots_[i].owned) slots_[i] = Slot{};
  }

 private:
  struct Slot {
    void* ptr = nullptr;
    std::shared_ptr<void> owned;
  };
  // One index per type for the whole process, handed out on first use.
  static size_t next_index();
  template <class T>
  static size_t index() {
    static const size_t i = next_index();
    return i;
  }
  Slot& slot(size_t i) {
    if (slots_.size() <= i) slots_.resize(i + 1);
    return slots_[i];
  }
  std::vector<Slot> slots_;
};

}  // namespace plc_cell
