// Real third-party masters against our slave: mbpoll, and the libmodbus reference
// programs compiled here from /usr/share/doc/libmodbus-dev/examples. Tests on the
// fixed port 1502 live in this one binary and run one after the other; no other test of the
// suite (which runs four at a time) may listen there, the docs' commands included.
#include <chrono>
#include <thread>

#include <gtest/gtest.h>

#include "helpers.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/io/serial_settings.h"
#include "plc_cell/modbus/rtu_server.h"
#include "plc_cell/modbus/tcp_server.h"

namespace plc_cell {
namespace modbus {
namespace {

using test::run;
const auto run_cmd = [](const std::string& c) { return test::run(c); };

uint16_t reg(Plc& plc, Area a, uint32_t i) {
  return plc.locked([&](ScanEngine&, Memory& m) { return m.reg(a, i); });
}

std::unique_ptr<TcpServer> tcp(Plc& plc, int port) {
  TcpServerOptions o;
  o.port = port;
  auto s = std::make_unique<TcpServer>(plc, o);
  s->start();
  return s;
}

// bandwidth-client reads 2000 coils and 125 registers from address 0: the
// user-defined map gives it M0..M1999 and R0..R124.
void bandwidth_layout(Plc& plc) {
  plc.locked([](ScanEngine&, Memory& m) {
    const uint16_t map[] = {0xA55A, 0, 0, 2000, 0, 0, 0, 0, 0, 0, 0, 0, 125};
    for (uint32_t i = 0; i < 13; ++i) m.set_reg(Area::R, 3968 + i, map[i]);
    return 0;
  });
}

TEST(ExternalClients, MbpollOverTcp) {
  Plc plc;
  auto s = tcp(plc, 0);
  const std::string base = "mbpoll -m tcp -p " + std::to_string(s->bound_port()) + " -a 1 -1 -o 5 ";
  auto o = run(base + "-t 4 -r 101 127.0.0.1 7 65528 9");  // 40101.. = R100..
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_EQ(reg(plc, Area::R, 100), 7);
  EXPECT_EQ(reg(plc, Area::R, 101), uint16_t(-8));
  o = run(base + "-t 4 -r 101 -c 3 127.0.0.1");
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_NE(o.text.find("[101]: \t7"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("[103]: \t9"), std::string::npos) << o.text;
  o = run(base + "-t 0 -r 1 127.0.0.1 1 0 1");  // 00001.. = Y0..
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_TRUE(plc.locked([](ScanEngine&, Memory& m) { return m.bit(Area::Y, 0) && !m.bit(Area::Y, 1) && m.bit(Area::Y, 2); }));
  o = run(base + "-t 0 -r 1 -c 3 127.0.0.1");
  EXPECT_NE(o.text.find("[3]: \t1"), std::string::npos) << o.text;
  o = run(base + "-t 4:hex -r 4169 127.0.0.1");  // R4168 is not mapped
  EXPECT_NE(o.text.find("Illegal data address"), std::string::npos) << o.text;
}

TEST(ExternalClients, MbpollOverRtuOnAPtyPair) {
  Plc plc;
  test::PtyPair pty("mbpoll");
  RtuServer s(plc, parse_serial_settings(pty.a + ":19200", "8E1"), 3);  // default format 8E1
  s.start();
  const std::string base = "mbpoll -m rtu -b 19200 -P even -d 8 -s 1 -a 3 -1 -o 5 ";
  auto o = run(base + "-t 4 -r 6001 " + pty.b + " 321 654");  // 46001.. = D0..
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_EQ(reg(plc, Area::D, 0), 321);
  EXPECT_EQ(reg(plc, Area::D, 1), 654);
  o = run(base + "-t 4 -r 6001 -c 2 " + pty.b);
  EXPECT_NE(o.text.find("[6002]: \t654"), std::string::npos) << o.text;
  o = run(base + "-t 0 -r 2001 " + pty.b + " 1");  // 02001 = M0
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_TRUE(plc.locked([](ScanEngine&, Memory& m) { return m.bit(Area::M, 0); }));
  // Another slave id on the line: no answer at all.
  o = run("mbpoll -m rtu -b 19200 -P even -a 4 -1 -o 0.3 -t 4 -r 1 " + pty.b);
  EXPECT_NE(o.text.find("timed out"), std::string::npos) << o.text;
  EXPECT_EQ(reg(plc, Area::R, 0), 0);
  // ... and the next request to us right after is answered (libmodbus would take it
  // for slave 4's reply without the short ignore window in RtuServer).
  o = run(base + "-t 4 -r 6002 " + pty.b);
  EXPECT_NE(o.text.find("[6002]: \t654"), std::string::npos) << o.text;
}

TEST(ExternalClients, RtuSlaveDropsBadFramesAndKeepsServing) {
  Plc plc;
  test::PtyPair pty("badrtu");
  RtuServer s(plc, parse_serial_settings(pty.a + ":19200", "8E1"), 1);
  s.start();
  {
    std::ofstream line(pty.b, std::ios::binary);
    const char bad_crc[] = {0x01, 0x06, 0x00, 0x00, 0x00, 0x09, char(0xFF), char(0xFF)};  // write R0 = 9
    line.write(bad_crc, sizeof bad_crc);
  }
  // The slave drops the frame and flushes its input; wait (bounded) until it has, so the
  // flush cannot take mbpoll's request with it.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (s.status().rejected == 0 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
  ASSERT_GE(s.status().rejected, 1u);
  const auto o = run("mbpoll -m rtu -b 19200 -P even -a 1 -1 -o 1 -t 4 -r 1 -c 2 " + pty.b);
  EXPECT_NE(o.text.find("[1]: \t0"), std::string::npos) << o.text;
  EXPECT_EQ(reg(plc, Area::R, 0), 0);  // the bad-CRC write changed nothing
}

TEST(ExternalClients, RandomTestClientOverTcp) {
  const std::string bin = test::build_example(
      "random-test-client", {{"modbus_set_debug(ctx, TRUE);", "modbus_set_debug(ctx, FALSE);"}}, "tcp");
  Plc plc;
  auto s = tcp(plc, 1502);
  const auto o = run(bin, 300);
  EXPECT_EQ(o.status, 0) << o.text;
  EXPECT_NE(o.text.find("Test: SUCCESS"), std::string::npos) << o.text;
  EXPECT_EQ(o.text.find("ERROR"), std::string::npos) << o.text;
}

TEST(ExternalClients, RandomTestClientOverRtu) {
  test::PtyPair pty("random");
  const std::string bin = test::build_example(
      "random-test-client",
      {{"modbus_set_debug(ctx, TRUE);", "modbus_set_debug(ctx, FALSE);"},
       {"ctx = modbus_new_tcp(\"127.0.0.1\", 1502);",
        "ctx = modbus_new_rtu(\"" + pty.b + "\", 19200, 'N', 8, 1); modbus_set_slave(ctx, SERVER_ID);"}},
      "rtu");
  Plc plc;
  RtuServer s(plc, parse_serial_settings(pty.a + ":19200:8N1"), 17);
  s.start();
  const auto o = run(bin, 300);
  EXPECT_EQ(o.status, 0) << o.text;
  EXPECT_NE(o.text.find("Test: SUCCESS"), std::string::npos) << o.text;
  EXPECT_EQ(o.text.find("ERROR"), std::string::npos) << o.text;
}

TEST(ExternalClients, BandwidthClientOverTcp) {
  // Fewer loops than the benchmark: this checks correctness, bench/ measures.
  const std::string bin = test::build_example("bandwidth-client", {{"n_loop = 100000;", "n_loop = 2000;"}}, "tcp");
  Plc plc;
  bandwidth_layout(plc);
  auto s = tcp(plc, 1502);
  const auto o = run(bin + " tcp", 300);
  EXPECT_EQ(o.status, 0) << o.text;
  EXPECT_NE(o.text.find("WRITE AND READ REGISTERS"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("registers/s"), std::string::npos) << o.text;
}

TEST(ExternalClients, BandwidthClientOverRtu) {
  test::PtyPair pty("bandwidth");
  const std::string bin = test::build_example("bandwidth-client", {{"/dev/ttyUSB1", pty.b}}, "rtu");
  Plc plc;
  bandwidth_layout(plc);
  RtuServer s(plc, parse_serial_settings(pty.a + ":115200:8N1"), 1);
  s.start();
  const auto o = run(bin + " rtu", 300);
  EXPECT_EQ(o.status, 0) << o.text;
  EXPECT_NE(o.text.find("WRITE AND READ REGISTERS"), std::string::npos) << o.text;
}

TEST(ExternalClients, PlcCellRunServesModbusTcp) {
  const std::string dir = PLC_CELL_SOURCE_DIR;
  test::Child run({PLC_CELL_TOOL, "run", "--config", dir + "/examples/conveyor/conveyor.yaml", "--modbus-tcp",
                   "127.0.0.1:15040", "--duration", "60s"});
  ASSERT_TRUE(run.wait_for("serving Modbus TCP 127.0.0.1:15040")) << run.seen();
  auto o = run_cmd("mbpoll -m tcp -p 15040 -a 1 -1 -o 5 -t 4 -r 4001 127.0.0.1 4242");  // R4000
  ASSERT_EQ(o.status, 0) << o.text;
  o = run_cmd("mbpoll -m tcp -p 15040 -a 1 -1 -o 5 -t 4 -r 4001 127.0.0.1");
  EXPECT_NE(o.text.find("[4001]: \t4242"), std::string::npos) << o.text;
}

TEST(ExternalClients, PlcCellRunRejectsBadModbusOptions) {
  auto o = run_cmd(std::string(PLC_CELL_TOOL) + " run --config " + PLC_CELL_SOURCE_DIR +
                   "/examples/conveyor/conveyor.yaml --modbus-rtu /dev/null:9600:9X1 --duration 1s");
  EXPECT_NE(o.status, 0);
  EXPECT_NE(o.text.find("9X1"), std::string::npos) << o.text;
  o = run_cmd(std::string(PLC_CELL_TOOL) + " run --config " + PLC_CELL_SOURCE_DIR +
              "/examples/conveyor/conveyor.yaml --modbus-gateway /dev/null --duration 1s");
  EXPECT_NE(o.status, 0);
  EXPECT_NE(o.text.find("needs a Modbus/TCP endpoint"), std::string::npos) << o.text;
}

}  // namespace
}  // namespace modbus
}  // namespace plc_cell
