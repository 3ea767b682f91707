// Faults on serial links (pty proxy): bytes dropped, flipped, cut; a silent line; the
// device removed and re-added. The servers stay up, report the fault, recover by
// themselves, and a rejected request never changes memory.
#include <gtest/gtest.h>
#include <modbus/modbus.h>

#include <map>
#include <set>

#include "plc_cell/core/address.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/client.h"
#include "plc_cell/fatek/server.h"
#include "plc_cell/modbus/rtu_server.h"
#include "pty_proxy.h"
#include "temp_dir.h"

using namespace plc_cell;

namespace {

Address d(uint32_t i) { return Address{Area::D, Width::Word, i}; }

std::unique_ptr<fatek::Client> serial_client(const std::string& path, int retries, int timeout_ms) {
  fatek::ClientOptions o;
  o.retries = retries;
  o.timeout_ms = timeout_ms;
  return std::make_unique<fatek::Client>(fatek::serial_transport(parse_serial_settings(path + ":9600:7E1")), o);
}

// Blocks on client requests (each bounded by its timeout) until one succeeds; false after n tries.
bool until_answered(fatek::Client& c, int n) {
  for (int i = 0; i < n; ++i) {
    try {
      c.status();
      return true;
    } catch (const fatek::CommError&) {
      c.transport().close();  // as fatek_bridge does: reopen on the next try
    } catch (const Error&) {
      c.transport().close();  // the device path is not there (yet)
    }
  }
  return false;
}

}  // namespace

TEST(LinkFaults, FatekSerialServerSurvivesDroppedFlippedAndCutBytes) {
  TempDir dir;
  PtyProxy proxy(dir.path(), 42);
  Plc plc;
  fatek::SerialServerOptions so;
  so.line = parse_serial_settings(proxy.device_link() + ":9600:7E1");
  so.frame_timeout_ms = 100;
  fatek::SerialServer server(plc, so);
  server.start();
  auto c = serial_client(proxy.client_link(), 0, 100);
  proxy.set_faults({0.05, 0.05, 0.05, false});
  std::map<uint32_t, uint32_t> sure;       // acknowledged values
  std::map<uint32_t, std::set<uint32_t>> maybe;  // unacknowledged writes may have happened
  int failures = 0;
  for (uint32_t i = 1; i <= 120; ++i) {
    const uint32_t k = i % 10;
    try {
      c->write(d(k), {i});
      sure[k] = i;
      maybe[k].clear();
    } catch (const fatek::CommError&) {
      maybe[k].insert(i);
      ++failures;
    }
  }
  EXPECT_GT(proxy.faults_injected(), 0u);
  EXPECT_GT(failures, 0);
  proxy.set_faults({});
  ASSERT_TRUE(until_answered(*c, 20));  // the line is clean again: served at once
  for (uint32_t k = 0; k < 10; ++k) {
    const uint32_t v = c->read(d(k), 1)[0];
    EXPECT_TRUE(v == sure[k] || maybe[k].count(v)) << "D" << k << " = " << v;
  }
  // Nothing outside what was written changed: damaged frames were refused, not misapplied.
  const auto rest = plc.read(d(10), 200);
  EXPECT_EQ(rest, std::vector<uint32_t>(200, 0));
  EXPECT_GT(server.status().rejected, 0u);
  EXPECT_TRUE(server.status().running);
}

TEST(LinkFaults, FatekSerialServerSilentLineThenBack) {
  TempDir dir;
  PtyProxy proxy(dir.path(), 7);
  Plc plc;
  fatek::SerialServerOptions so;
  so.line = parse_serial_settings(proxy.device_link() + ":9600:7E1");
  fatek::SerialServer server(plc, so);
  server.start();
  auto c = serial_client(proxy.client_link(), 0, 150);
  c->write(d(1), {5});
  proxy.set_faults({0, 0, 0, true});
  EXPECT_THROW(c->write(d(1), {6}), fatek::CommError);
  proxy.set_faults({});
  ASSERT_TRUE(until_answered(*c, 20));
  EXPECT_EQ(c->read(d(1), 1)[0], 5u);  // the request that never arrived changed nothing
}

TEST(LinkFaults, FatekSerialServerReopensARemovedDevice) {
  TempDir dir;
  PtyProxy proxy(dir.path(), 1);
  Plc plc;
  fatek::SerialServerOptions so;
  so.line = parse_serial_settings(proxy.device_link() + ":9600:7E1");
  fatek::SerialServer server(plc, so);
  server.start();
  auto c = serial_client(proxy.client_link(), 0, 200);
  c->write(d(2), {77});
  proxy.unplug();
  // Each failed request blocks for its timeout; the server notices the hang-up meanwhile.
  for (int i = 0; i < 20 && server.status().link_up; ++i) EXPECT_THROW(c->status(), fatek::CommError);
  EXPECT_FALSE(server.status().link_up);
  EXPECT_NE(server.status().last_error.find("serial device lost"), std::string::npos) << server.status().last_error;
  EXPECT_TRUE(server.status().running);
  proxy.replug();
  ASSERT_TRUE(until_answered(*c, 50));
  EXPECT_TRUE(server.status().link_up);
  EXPECT_GE(server.status().reopened, 1u);
  EXPECT_EQ(c->read(d(2), 1)[0], 77u);
  c->write(d(3), {1});
  EXPECT_EQ(plc.read(d(3), 1)[0], 1u);
}

// The master's side (what fatek_bridge does): on a dead line it closes the transport, and the
// next request opens the path again.
TEST(LinkFaults, FatekSerialClientReopensItsRemovedDevice) {
  TempDir dir;
  PtyProxy proxy(dir.path(), 5);
  Plc plc;
  fatek::SerialServerOptions so;
  so.line = parse_serial_settings(proxy.device_link() + ":9600:7E1");
  fatek::SerialServer server(plc, so);
  server.start();
  auto c = serial_client(proxy.client_link(), 0, 200);
  c->write(d(4), {44});
  proxy.unplug_client();
  EXPECT_THROW(c->write(d(4), {45}), fatek::CommError);
  c->transport().close();
  EXPECT_THROW(c->status(), fatek::CommError);  // still gone: the open fails
  c->transport().close();
  proxy.replug_client();
  ASSERT_TRUE(until_answered(*c, 20));
  EXPECT_EQ(c->read(d(4), 1)[0], 44u);  // the write sent into the void changed nothing
  EXPECT_TRUE(server.status().link_up);  // the server's side never went away
}

TEST(LinkFaults, ModbusRtuServerReopensARemovedDevice) {
  TempDir dir;
  PtyProxy proxy(dir.path(), 3);
  Plc plc;
  modbus::RtuServer server(plc, parse_serial_settings(proxy.device_link() + ":19200:8E1"), 1);
  server.start();
  modbus_t* m = modbus_new_rtu(proxy.client_link().c_str(), 19200, 'E', 8, 1);
  ASSERT_NE(m, nullptr);
  modbus_set_slave(m, 1);
  modbus_set_response_timeout(m, 0, 300000);
  ASSERT_EQ(modbus_connect(m), 0);
  ASSERT_EQ(modbus_write_register(m, 6002, 77), 1);  // D2
  proxy.unplug();
  uint16_t v = 0;
  for (int i = 0; i < 20 && server.status().link_up; ++i) EXPECT_EQ(modbus_read_registers(m, 6002, 1, &v), -1);
  EXPECT_FALSE(server.status().link_up);
  EXPECT_NE(server.status().last_error.find("serial device lost"), std::string::npos) << server.status().last_error;
  proxy.replug();
  bool back = false;
  for (int i = 0; i < 50 && !back; ++i) {
    back = modbus_read_registers(m, 6002, 1, &v) == 1;
    if (!back) modbus_flush(m);
  }
  ASSERT_TRUE(back);
  EXPECT_EQ(v, 77);
  EXPECT_TRUE(server.status().link_up);
  EXPECT_GE(server.status().reopened, 1u);
  modbus_close(m);
  modbus_free(m);
}
