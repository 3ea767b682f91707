#pragma once
// The lockstep engine (docs/native-engine.md, "Lockstep"): the PLC runs its program on the
// native engine, and a twin, a second PLC built the same way, runs the same program on the
// interpreter with the same inputs; their whole memories are compared after every run of
// the program (each scan's main program, each interrupt routine) and after every scan.
//
// The twin is whatever the PLC is: a bare PLC's is a bare PLC (made here); a cell's is the
// whole cell, with its counters, axes, modules, RTC and simulation, which the layers that
// build cells make (sim/lockstep_cells.h) and hand over with what else they must bring
// from the PLC to the twin before each scan (`mirror`: the simulation's overrides).
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/memory.h"

namespace plc_cell {

class Plc;
class ScanEngine;

// Empty when the two images are equal; otherwise the first difference: the address, both
// values, the instruction of program that writes the address (file:line) and `what` (the run).
std::string first_difference(const Memory& native, const Memory& interpreter, const Program& program,
                             const std::string& what);

// What sees every run of a scan engine's program and every scan (ScanEngine::observe_runs).
class RunObserver {
 public:
  virtual ~RunObserver() = default;
  // At the start of every scan, before the input image.
  virtual void before_scan(uint64_t /*now_us*/) {}
  // After the main program (routine empty) or a routine ran at now_us; ok: without a
  // runtime fault, else fault says which. Non-empty: the engine stops with that fault.
  virtual std::string after_run(const std::string& routine, uint64_t now_us, bool ok, const std::string& fault) = 0;
  // At the end of every scan. Non-empty: the engine stops with that fault.
  virtual std::string after_scan() { return {}; }
};

class Lockstep final : public RunObserver {
 public:
  // A bare twin of its own, for a PLC with no subsystem hooked.
  explicit Lockstep(const FunctionTable& functions);
  // twin: a PLC built as the primary one, which this object scans, on the interpreter,
  // before each scan of the primary (it must outlive this object). mirror: called with both
  // PLCs locked before each twin scan, after the memory, the input terminals, the mode and
  // the program were brought over.
  Lockstep(Plc& twin, std::function<void()> mirror);
  ~Lockstep() override;
  Lockstep(const Lockstep&) = delete;
  Lockstep& operator=(const Lockstep&) = delete;

  // ScanEngine::set_lockstep: the primary's engine and memory (under its lock from now on).
  void bind(ScanEngine& primary, Memory& memory);
  // The twin's scan at now_us: what inputs, clients, forcing, RUN/STOP and an online change
  // brought into the primary since its last scan goes to the twin first.
  void before_scan(uint64_t now_us) override;
  std::string after_run(const std::string& routine, uint64_t now_us, bool ok, const std::string& fault) override;
  std::string after_scan() override;
  // "a bare PLC" or "the whole cell": what the twin is, for engine_status().
  const char* twin_kind() const { return own_twin_ ? "a bare PLC" : "the whole cell"; }

 private:
  class Recorder;
  struct Image {
    std::string routine;
    bool ok = true;
    std::string fault;
    Memory memory;
  };
  // "scan 12 at 0.012000 s", "routine HSC0I at 0.011234 s": where a difference was found.
  std::string what(const std::string& routine, uint64_t now_us) const;

  std::unique_ptr<Plc> own_twin_;  // a bare PLC's twin
  Plc& twin_;
  std::function<void()> mirror_;
  std::unique_ptr<Recorder> recorder_;
  ScanEngine* primary_ = nullptr;
  Memory* memory_ = nullptr;
  uint64_t loads_seen_ = 0;   // the primary's program loads the twin has followed
  uint64_t starts_seen_ = 0;  // and its STOP -> RUN
  std::vector<Image> images_;   // the twin's, after each run of its scan (storage reused)
  size_t recorded_ = 0, compared_ = 0;
  bool reported_ = false;  // a difference stopped the primary in this scan
};

}  // namespace plc_cell
