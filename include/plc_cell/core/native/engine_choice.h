#pragma once
// Which engine runs the IL program (docs/native-engine.md).
#include <string>

namespace plc_cell {

enum class EngineChoice {
  Interpreter,  // the threaded interpreter
  Native,       // the networks compiled to machine code at load time (flow on the interpreter)
  Lockstep,     // both, on two copies of the memory, compared after every scan and routine
};

// "interpreter", "native" or "lockstep"; false for anything else.
bool parse_engine_choice(const std::string& text, EngineChoice* out);
const char* engine_choice_name(EngineChoice e);

}  // namespace plc_cell
