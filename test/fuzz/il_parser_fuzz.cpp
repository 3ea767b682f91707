// Any program text: the IL parser either returns a program or throws SourceError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "plc_cell/core/error.h"
#include "plc_cell/core/function_table.h"
#include "plc_cell/core/il_parser.h"
#include "plc_cell/sim/soft_cell.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const plc_cell::FunctionTable fns = plc_cell::SoftCell::functions();  // a cell's whole set
  try {
    plc_cell::parse_program(std::string(reinterpret_cast<const char*>(data), size), "fuzz.il", fns);
  } catch (const plc_cell::Error&) {
  }
  return 0;
}
