// The gateway: TCP client -> gateway -> RTU slave on a pty, TRi semantics.
#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include <gtest/gtest.h>
#include <modbus/modbus.h>

#include "helpers.h"
#include "../reliability/pty_proxy.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/modbus/gateway.h"
#include "plc_cell/modbus/rtu_server.h"

namespace plc_cell {
namespace modbus {
namespace {

GatewayOptions options(const std::string& dev) {
  GatewayOptions o;
  o.tcp.port = 0;
  o.tcp.own_unit = 1;
  o.line = parse_serial_settings(dev + ":115200:8E1");
  return o;
}

modbus_t* client(int port, int unit) {
  modbus_t* c = modbus_new_tcp("127.0.0.1", port);
  modbus_set_slave(c, unit);
  modbus_set_response_timeout(c, 10, 0);
  EXPECT_EQ(modbus_connect(c), 0);
  return c;
}

void done(modbus_t* c) {
  modbus_close(c);
  modbus_free(c);
}

TEST(Gateway, RoutesByUnitId) {
  test::PtyPair pty("gw_route");
  Plc own, remote;
  own.locked([](ScanEngine&, Memory& m) { m.set_reg(Area::R, 0, 111); return 0; });
  remote.locked([](ScanEngine&, Memory& m) { m.set_reg(Area::R, 0, 555); return 0; });
  RtuServer slave(remote, parse_serial_settings(pty.b + ":115200:8E1"), 5);
  slave.start();
  GatewayServer gw(own, options(pty.a));
  gw.start();
  uint16_t r[1];
  for (int unit : {1, 0, 255}) {  // the PLC itself
    modbus_t* c = client(gw.bound_port(), unit);
    ASSERT_EQ(modbus_read_registers(c, 0, 1, r), 1) << unit;
    EXPECT_EQ(r[0], 111) << unit;
    done(c);
  }
  modbus_t* c = client(gw.bound_port(), 5);
  ASSERT_EQ(modbus_read_registers(c, 0, 1, r), 1);
  EXPECT_EQ(r[0], 555);
  ASSERT_EQ(modbus_write_register(c, 3, 77), 1);
  EXPECT_EQ(remote.locked([](ScanEngine&, Memory& m) { return m.reg(Area::R, 3); }), 77);
  EXPECT_EQ(own.locked([](ScanEngine&, Memory& m) { return m.reg(Area::R, 3); }), 0);
  // The slave's own exception comes back through the gateway unchanged.
  EXPECT_EQ(modbus_read_registers(c, 4168, 1, r), -1);
  EXPECT_EQ(errno, EMBXILADD);
  done(c);
  gw.stop();
}

// The gateway's line is held by its path: an adapter pulled out and plugged back in is
// found again. Meanwhile the forwarded requests get 0B; afterwards they are answered.
TEST(Gateway, ALineThatWentAwayIsOpenedAgain) {
  TempDir dir;
  PtyProxy proxy(dir.path(), 1);
  Plc own, remote;
  remote.locked([](ScanEngine&, Memory& m) { m.set_reg(Area::R, 0, 555); return 0; });
  RtuServer slave(remote, parse_serial_settings(proxy.device_link() + ":115200:8E1"), 5);
  slave.start();
  GatewayOptions o = options(proxy.client_link());
  o.wait_ms = 100;
  o.retries = 0;
  GatewayServer gw(own, o);
  gw.start();
  modbus_t* c = client(gw.bound_port(), 5);
  uint16_t r[1] = {0};
  ASSERT_EQ(modbus_read_registers(c, 0, 1, r), 1);
  EXPECT_EQ(r[0], 555);
  proxy.unplug_client();
  EXPECT_EQ(modbus_read_registers(c, 0, 1, r), -1);
  EXPECT_EQ(errno, EMBXGTAR);
  proxy.replug_client();
  r[0] = 0;
  bool back = false;
  for (int i = 0; i < 50 && !back; ++i) back = modbus_read_registers(c, 0, 1, r) == 1;  // each bounded by wait
  EXPECT_TRUE(back);
  EXPECT_EQ(r[0], 555);
  done(c);
  gw.stop();
}

// Reads one RTU frame (8 bytes: a read request) from the line, or times out.
bool sniff_request(int fd, uint8_t unit, int timeout_ms = 5000) {
  uint8_t buf[8];
  size_t got = 0;
  while (got < sizeof buf) {
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, timeout_ms) <= 0) return false;
    const ssize_t n = read(fd, buf + got, sizeof buf - got);
    if (n <= 0) return false;
    got += size_t(n);
  }
  return buf[0] == unit && buf[1] == 3;
}

TEST(Gateway, SilentSlaveGets0BAfterRetriesAndOthersAreServed) {
  test::PtyPair pty("gw_silent");
  const int line = open(pty.b.c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(line, 0);
  Plc own;
  own.locked([](ScanEngine&, Memory& m) { m.set_reg(Area::R, 0, 111); return 0; });
  GatewayOptions o = options(pty.a);
  o.max_pending = 1;
  GatewayServer gw(own, o);
  gw.start();

  int rc = 0, err = 0;
  double elapsed_ms = 0;
  std::thread first([&] {
    modbus_t* c = client(gw.bound_port(), 9);
    uint16_t r[1];
    const auto t0 = std::chrono::steady_clock::now();
    rc = modbus_read_registers(c, 0, 1, r);
    err = errno;
    elapsed_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    done(c);
  });
  ASSERT_TRUE(sniff_request(line, 9));  // attempt 1 is on the line: the line is busy
  {
    // Another client of the PLC itself is served meanwhile...
    modbus_t* c = client(gw.bound_port(), 1);
    uint16_t r[1];
    ASSERT_EQ(modbus_read_registers(c, 0, 1, r), 1);
    EXPECT_EQ(r[0], 111);
    // ... and one for the busy line beyond the queue bound gets 06 at once.
    modbus_set_slave(c, 7);
    EXPECT_EQ(modbus_read_registers(c, 0, 1, r), -1);
    EXPECT_EQ(errno, EMBXSBUSY);
    done(c);
  }
  EXPECT_TRUE(sniff_request(line, 9));  // retry 1
  EXPECT_TRUE(sniff_request(line, 9));  // retry 2
  first.join();
  EXPECT_EQ(rc, -1);
  EXPECT_EQ(err, EMBXGTAR);  // 0B: target device failed to respond
  const double bound = o.wait_ms * (o.retries + 1);
  EXPECT_GE(elapsed_ms, bound);         // it did wait out every attempt
  EXPECT_LT(elapsed_ms, bound + 2000);  // and answered once they were done (loose: not a speed test)
  EXPECT_FALSE(sniff_request(line, 9, 300));  // no fourth attempt
  close(line);
  gw.stop();
}

}  // namespace
}  // namespace modbus
}  // namespace plc_cell
