#pragma once
// The scan cycle: input image -> program -> output image, with special relays,
// timers, RUN/STOP and the watchdog. Not thread-safe; the Plc facade locks around it.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "plc_cell/core/extension_slots.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/memory.h"
#include "plc_cell/core/native/engine_choice.h"
#include "plc_cell/core/native/lockstep.h"
#include "plc_cell/core/scan_stats.h"

namespace plc_cell {

enum class RunMode : uint8_t { Stop, Run };

class ScanEngine;

// Hooks for subsystems that live beside the program (high-speed I/O, motion, simulation).
class ScanHook {
 public:
  virtual ~ScanHook() = default;
  // add_hook/remove_hook: a subsystem whose FUN handlers need it puts itself in the
  // engine's extension slots here, so it is reachable exactly while it is hooked.
  virtual void attached(ScanEngine& /*engine*/) {}
  virtual void detached(ScanEngine& /*engine*/) {}
  virtual void before_inputs(uint64_t /*now_us*/) {}   // drive input terminals (simulation)
  virtual void before_program(uint64_t /*now_us*/) {}  // after the input image is taken
  virtual void after_program(uint64_t /*now_us*/) {}   // before the output image is given
  virtual void on_stop() {}
  // STOP -> RUN, after the non-retentive memory is cleared: what must read right before
  // the first scan of the run (the clock registers) is put back here.
  virtual void on_run() {}

  // The scan phases a hook of type T has code for. A phase T does not declare is
  // ScanHook's empty one (its member pointer's type names ScanHook), and the engine does
  // not call it: a unit with nothing to do before the inputs costs that phase nothing.
  // Only a final T is read this way; through a pointer to a base a derived override
  // could hide, so every phase is called.
  enum Phase : unsigned { kBeforeInputs = 1u, kBeforeProgram = 2u, kAfterProgram = 4u, kEveryPhase = 7u };
  template <class T>
  static constexpr unsigned phases_of() {
    if constexpr (!std::is_final<T>::value) {
      return kEveryPhase;
    } else {
      using Step = void (ScanHook::*)(uint64_t);
      return (std::is_same<decltype(&T::before_inputs), Step>::value ? 0u : kBeforeInputs) |
             (std::is_same<decltype(&T::before_program), Step>::value ? 0u : kBeforeProgram) |
             (std::is_same<decltype(&T::after_program), Step>::value ? 0u : kAfterProgram);
    }
  }
};

class ScanEngine {
 public:
  ScanEngine(Memory& mem, const FunctionTable& functions);

  void load(const Program& program);
  // A change in RUN (docs/online-change.md): swapped in at this scan boundary keeping the
  // memory, the timers and the edge memories the new program still has, without a first-scan
  // pulse. In STOP it is load(). The caller checks online_change_refusals first.
  void load_online(const Program& program);
  // Whether the last load was load_online (what a lockstep twin repeats).
  bool last_load_online() const { return last_load_online_; }
  const Program& program() const { return interp_.program(); }
  // How many programs were loaded, and how many times STOP -> RUN happened: what a lockstep
  // twin follows (core/native/lockstep.h).
  uint64_t program_loads() const { return program_loads_; }
  uint64_t run_starts() const { return run_starts_; }
  Interpreter& interpreter() { return interp_; }
  const Interpreter& interpreter() const { return interp_; }

  // Which engine runs the program (docs/native-engine.md); effective at once, on the
  // loaded program too, with its edge memories and timers kept. Lockstep makes a bare PLC
  // its twin when none was given (set_lockstep); an engine with subsystems hooked needs
  // its whole cell as the twin, and is refused (Error) without one.
  void set_engine(EngineChoice e);
  // Lockstep with this twin (a whole cell's: sim/lockstep_cells.h).
  void set_lockstep(std::unique_ptr<Lockstep> twin);
  // What sees every run and scan (the lockstep twin's recorder); nullptr: nothing.
  void observe_runs(RunObserver* o) { runs_ = o; }
  EngineChoice engine() const { return engine_; }
  // What actually runs the program, and why (the native engine may fall back).
  std::string engine_status() const;
  // The native engine was chosen but the interpreter runs the loaded program.
  bool engine_fell_back() const { return engine_ != EngineChoice::Interpreter && interp_.loaded() && !interp_.native_active(); }
  // An interrupt service routine, on the chosen engine (in lockstep, on both, compared).
  // False on a runtime fault or a lockstep difference: the reason is in *why.
  bool run_routine(const std::string& label, uint64_t now_us, std::string* why);

  void set_retentive(std::vector<AreaRange> ranges) { retentive_ = std::move(ranges); }
  const std::vector<AreaRange>& retentive() const { return retentive_; }
  void set_watchdog_us(uint64_t us) { watchdog_us_ = us; }
  uint64_t watchdog_us() const { return watchdog_us_; }

  RunMode mode() const { return mode_; }
  // STOP -> RUN clears non-retentive memory and starts with the first-scan pulse.
  // Returns false (and stays in STOP) if there is no program.
  bool set_mode(RunMode m);

  // The input terminals: what the cell or its simulation presents on X0..X255.
  void set_input(uint32_t x, bool v) { inputs_[x] = v; }
  bool input(uint32_t x) const { return inputs_[x]; }
  const uint8_t* inputs() const { return inputs_.data(); }  // 256 bytes, 0 or 1 each

  // One scan at time now_us (microseconds on the engine's clock, virtual or steady).
  void scan(uint64_t now_us) {
    if (runs_) return scan_observed(now_us);
    cycle(now_us);
  }
  uint64_t now_us() const { return now_us_; }

  // The real-time loop reports each scan's duration; past the watchdog the PLC stops.
  void report_cycle(uint64_t exec_ns, uint64_t wake_latency_ns, uint64_t missed_periods, uint64_t missed_off_cpu = 0);

  const ScanStats& stats() const { return stats_; }
  void reset_stats() { stats_ = {}; }
  // Why the engine stopped by itself (runtime fault or watchdog); empty if it did not.
  const std::string& fault() const { return fault_; }
  bool watchdog_tripped() const { return watchdog_tripped_; }

  template <class T>
  void add_hook(T* h) {
    add_hook(h, ScanHook::phases_of<T>());
  }
  void add_hook(ScanHook* h, unsigned phases);
  void remove_hook(ScanHook* h);
  const std::vector<ScanHook*>& hooks() const { return hooks_; }
  // The subsystems' per-PLC objects, for the FUN handlers (core/extension_slots.h).
  ExtensionSlots& extensions() { return extensions_; }
  const ExtensionSlots& extensions() const { return extensions_; }
  // A subsystem's runtime fault (an interrupt routine that failed): STOP with this reason.
  void stop_with_fault(const std::string& why) { fault_stop(why); }

 private:
  void cycle(uint64_t now_us);  // the scan itself
  // The scan and each run told to the observer: out of line, so that the usual scan does
  // not pay for their frames.
  void scan_observed(uint64_t now_us);
  void update_special_relays();
  // Runs the main program (routine empty) or a routine.
  bool run_program(const std::string& routine, uint64_t now_us, uint32_t dt_us, std::string* why);
  bool run_observed(const std::string& routine, uint64_t now_us, uint32_t dt_us, std::string* why);
  bool run_engine(const std::string& routine, uint64_t now_us, uint32_t dt_us, std::string* why);
  void fault_stop(const std::string& why);

  Memory& mem_;
  const FunctionTable& functions_;
  Interpreter interp_;
  // What interp_ starts as; the constructor then chooses kDefaultEngine.
  EngineChoice engine_ = EngineChoice::Interpreter;
  std::unique_ptr<Lockstep> lockstep_;  // the twin, in lockstep only
  RunObserver* runs_ = nullptr;         // lockstep_, or the recorder of a twin
  uint64_t program_loads_ = 0, run_starts_ = 0;
  bool last_load_online_ = false;
  std::vector<AreaRange> retentive_;
  std::vector<ScanHook*> hooks_;
  // The hooks each scan phase calls (ScanHook::phases_of), in the order they were added.
  std::vector<ScanHook*> before_inputs_, before_program_, after_program_;
  ExtensionSlots extensions_;
  std::array<uint8_t, 256> inputs_{};  // 0/1, one byte each: the input image copies them branch-free
  RunMode mode_ = RunMode::Stop;
  bool first_scan_ = false;
  bool have_time_ = false;
  uint64_t now_us_ = 0;
  // The four clock relays hold for a 5 ms half period of the fastest: their bytes, found
  // once per half period (update_special_relays).
  uint64_t clock_half_ = UINT64_MAX;
  uint64_t clock_bytes_ = 0;
  uint64_t watchdog_us_ = 200000;
  ScanStats stats_;
  std::string fault_;
  bool watchdog_tripped_ = false;
};

}  // namespace plc_cell
