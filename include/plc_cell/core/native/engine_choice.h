#pragma once
// Which engine runs the IL program (docs/native-engine.md).
#include <string>

namespace plc_cell {

enum class EngineChoice {
  Interpreter,  // the threaded interpreter
  Native,       // the networks compiled to machine code at load time (flow on the interpreter)
  Lockstep,     // both, on two copies of the memory, compared after every scan and routine
};

// What a scan engine and a cell's plc.engine start with; the native engine falls back to
// the interpreter by itself where it cannot generate code.
constexpr EngineChoice kDefaultEngine = EngineChoice::Native;

// "interpreter", "native" or "lockstep"; false for anything else.
bool parse_engine_choice(const std::string& text, EngineChoice* out);
const char* engine_choice_name(EngineChoice e);

}  // namespace plc_cell
