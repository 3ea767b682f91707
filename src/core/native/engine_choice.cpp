#include "plc_cell/core/native/engine_choice.h"

namespace plc_cell {

bool parse_engine_choice(const std::string& text, EngineChoice* out) {
  for (EngineChoice e : {EngineChoice::Interpreter, EngineChoice::Native, EngineChoice::Lockstep})
    if (text == engine_choice_name(e)) {
      *out = e;
      return true;
    }
  return false;
}

const char* engine_choice_name(EngineChoice e) {
  switch (e) {
    case EngineChoice::Interpreter: return "interpreter";
    case EngineChoice::Native: return "native";
    case EngineChoice::Lockstep: return "lockstep";
  }
  return "interpreter";
}

}  // namespace plc_cell
