#pragma once
// The lockstep engine (docs/native-engine.md): the interpreter runs beside the native
// engine on its own copy of the memory, and the two images are compared after every scan
// and every interrupt routine.
#include <cstdint>
#include <string>

#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/memory.h"

namespace plc_cell {

// Empty when the two images are equal; otherwise the first difference: the address, both
// values, the instruction of program that writes the address (file:line) and `what` (the run).
std::string first_difference(const Memory& native, const Memory& interpreter, const Program& program,
                             const std::string& what);

class Lockstep {
 public:
  explicit Lockstep(const FunctionTable& functions);

  void load(const Program& program) { shadow_.load(program); }
  void reset_state() { shadow_.reset_state(); }

  // Before each run: the native engine's memory (with what inputs, servers and subsystems
  // wrote since) and its interpreter's settings become the shadow's.
  void sync(const Memory& primary, const Interpreter& settings);
  // Runs the shadow the way the native engine just ran (routine empty: the main program).
  // The shadow has no scan engine: FUN instructions that act on the cell's subsystems
  // act on the cell once, from the native engine.
  bool run(const std::string& routine, uint64_t now_us, uint32_t dt_us);
  const std::string& fault() const { return shadow_.fault(); }

  // first_difference() between the native engine's memory and the shadow's.
  std::string compare(const Memory& native, const std::string& what) const {
    return first_difference(native, memory_, shadow_.program(), what);
  }

 private:
  Memory memory_;
  Interpreter shadow_;
};

}  // namespace plc_cell
