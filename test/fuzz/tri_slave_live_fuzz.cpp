// Any bytes on a TRi host-link line, decoded and answered by the servers' own entry points
// (tri::Decoder, tri::Slave::handle) on a live Plc whose scan runs: no crash, no sanitizer
// report, and the scan never waits past its budget (live_plc.h). The first byte chooses
// whether the wildcard FCS is accepted, so both protocol settings are reached.
#include <cstddef>
#include <cstdint>
#include <string>

#include "live_plc.h"
#include "plc_cell/tri/frame.h"
#include "plc_cell/tri/slave.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  live_plc::Live& l = live_plc::live();
  // Restricted writes also refuse IW, halt and resume: the ID stays 1 and the PLC in RUN,
  // so every input meets the same slave and a fault can only be a finding.
  static plc_cell::tri::Slave* slave = [&l] {
    auto* s = new plc_cell::tri::Slave(l.plc, 1);
    s->set_writable(l.writable);
    return s;
  }();
  plc_cell::tri::Decoder dec(/*wildcard=*/data[0] & 1);
  std::string out;
  dec.feed(data + 1, size - 1, [&](const plc_cell::tri::Decoder::Event& e) { slave->handle(e, out); });
  live_plc::check_scan(l);
  return 0;
}
