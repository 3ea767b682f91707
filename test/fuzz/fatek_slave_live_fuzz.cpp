// Any bytes on a FATEK line, decoded and answered by the servers' own entry points
// (fatek::Decoder, fatek::Slave::handle) on a live Plc whose scan runs: no crash, no
// sanitizer report, and the scan never waits past its budget (live_plc.h).
#include <cstddef>
#include <cstdint>
#include <string>

#include "live_plc.h"
#include "plc_cell/fatek/frame.h"
#include "plc_cell/fatek/slave.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  live_plc::Live& l = live_plc::live();
  static plc_cell::fatek::Slave* slave = [&l] {
    auto* s = new plc_cell::fatek::Slave(l.plc, 1);
    s->set_writable(l.writable);
    return s;
  }();
  plc_cell::fatek::Decoder dec;
  std::string out;
  dec.feed(data, size, [&](const plc_cell::fatek::Frame& f) { slave->handle(f, out); },
           [](plc_cell::fatek::Decoder::Fault) {});
  live_plc::check_scan(l);
  return 0;
}
