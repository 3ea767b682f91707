// Any bytes on a FATEK line: the decoder and the slave (on a real Plc) must never crash,
// hang or leak, whatever arrives.
#include <cstddef>
#include <cstdint>
#include <string>

#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/frame.h"
#include "plc_cell/fatek/slave.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static plc_cell::Plc plc;
  static plc_cell::fatek::Slave slave(plc, 1);
  plc_cell::fatek::Decoder dec;
  std::string out;
  dec.feed(data, size, [&](const plc_cell::fatek::Frame& f) { slave.handle(f, out); },
           [](plc_cell::fatek::Decoder::Fault) {});
  return 0;
}
