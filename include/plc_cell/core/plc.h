#pragma once
// The soft PLC as servers and nodes see it: memory, engine and program behind one
// mutex, so that every request is atomic with respect to the scan.
#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/durability.h"
#include "plc_cell/core/function_table.h"
#include "plc_cell/core/handoff_mutex.h"
#include "plc_cell/core/memory.h"
#include "plc_cell/core/scan_engine.h"

namespace plc_cell {

enum class ForceAction : uint8_t { Disable, Enable, Set, Reset };  // FATEK command 42 order

class Plc {
 public:
  explicit Plc(FunctionTable functions = FunctionTable::with_core_functions());
  Plc(const Plc&) = delete;
  Plc& operator=(const Plc&) = delete;

  // Parses and swaps in a program; on a parse error throws SourceError and keeps the old one.
  void load_program_text(const std::string& text, const std::string& file);
  void load_program_file(const std::string& path);
  void load_program(const Program& program);

  // Whole-request access: validated first, then applied under the lock, or nothing changes.
  std::vector<uint32_t> read(const Address& start, uint32_t count) const;
  void write(const Address& start, const std::vector<uint32_t>& values);
  void force(const Address& bit, ForceAction action);
  bool set_mode(RunMode m);
  RunMode mode() const;

  // Presents a level on an input terminal X (what a sensor or the simulation drives).
  void set_input(uint32_t x, bool v);

  // One scan at time now_us.
  void scan(uint64_t now_us);

  // Runs fn with the lock held; for anything that must see one consistent state.
  template <typename F>
  auto locked(F&& fn) -> decltype(fn(std::declval<ScanEngine&>(), std::declval<Memory&>())) {
    std::lock_guard<HandoffMutex> lk(mu_);
    return fn(engine_, memory_);
  }
  template <typename F>
  auto locked(F&& fn) const -> decltype(fn(std::declval<const ScanEngine&>(), std::declval<const Memory&>())) {
    std::lock_guard<HandoffMutex> lk(mu_);
    return fn(engine_, memory_);
  }
  // Runs step with the lock held while it returns true: a virtual-time run, scan after
  // scan. Between two steps a waiting client has the lock first (handoff_mutex.h).
  template <typename F>
  void locked_steps(F&& step) {
    std::lock_guard<HandoffMutex> lk(mu_);
    while (step(engine_, memory_)) mu_.let_waiters_in();
  }
  // Clients waiting for the lock (tests).
  uint64_t waiting_clients() const { return mu_.waiting(); }

  const FunctionTable& functions() const { return functions_; }

  // Persistence of acknowledged writes. write() and force() commit by themselves; a
  // server that changes memory through locked() calls commit() before it replies.
  // Without a Durability attached commit() does nothing. The Durability must outlive
  // its attachment (detach with nullptr first).
  void set_durability(Durability* d) { durability_.store(d); }
  void commit();
  bool has_durability() const { return durability_.load() != nullptr; }

 private:
  void write_unlocked(const Address& a, uint32_t v);
  void force_apply(const Address& a, ForceAction action);  // takes the lock, no commit

  mutable HandoffMutex mu_;
  FunctionTable functions_;
  Memory memory_;
  ScanEngine engine_;
  std::atomic<Durability*> durability_{nullptr};
};

}  // namespace plc_cell
