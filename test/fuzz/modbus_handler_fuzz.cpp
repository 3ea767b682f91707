// Any bytes from a Modbus/TCP client, framed by libmodbus's modbus_receive and answered by
// the server's own entry point (modbus::handle_request) on a live Plc whose scan runs: no
// crash, no sanitizer report, and the scan never waits past its budget (live_plc.h).
#include <sys/socket.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>

#include <modbus/modbus.h>

#include "live_plc.h"
#include "plc_cell/modbus/slave_handler.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  live_plc::Live& l = live_plc::live();
  static modbus_t* ctx = [] {
    modbus_t* c = modbus_new_tcp("127.0.0.1", 502);
    modbus_set_indication_timeout(c, 0, 1000);  // the input is all there: do not wait for more
    // libmodbus sleeps this long before some exception replies (its "flush" after a bad
    // request). 120 ms instead of the default 500 ms keeps each input fast, and still longer
    // than the scan budget (100 ms): a sleep under the PLC lock remains a finding.
    modbus_set_response_timeout(c, 0, 120000);
    return c;
  }();
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) return 0;
  // The whole input as the client's stream, then end of stream.
  (void)!::write(sv[1], data, size);
  ::shutdown(sv[1], SHUT_WR);
  modbus_set_socket(ctx, sv[0]);
  uint8_t req[MODBUS_TCP_MAX_ADU_LENGTH];
  for (int frames = 0; frames < 64; ++frames) {  // a 512-byte input holds at most 64 frames
    const int rc = modbus_receive(ctx, req);
    if (rc <= 0) break;
    plc_cell::modbus::handle_request(ctx, l.plc, req, rc, &l.writable);
    uint8_t sink[1024];
    while (::recv(sv[1], sink, sizeof sink, MSG_DONTWAIT) > 0) {
    }
  }
  ::close(sv[0]);
  ::close(sv[1]);
  live_plc::check_scan(l);
  return 0;
}
