// Safe network defaults: loopback unless told otherwise, writable ranges answered with the
// protocol's own error and no change to memory, connection cap and idle timeout as set.
#include <gtest/gtest.h>
#include <arpa/inet.h>
#include <modbus/modbus.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>

#include "plc_cell/core/address.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/core/writable_ranges.h"
#include "plc_cell/fatek/client.h"
#include "plc_cell/fatek/server.h"
#include "plc_cell/modbus/slave_servers.h"
#include "plc_cell/modbus/tcp_server.h"

using namespace plc_cell;

namespace {

Address at(const char* s) { return parse_address(s); }

std::unique_ptr<fatek::Client> fatek_client(int port) {
  fatek::ClientOptions o;
  o.retries = 0;
  o.timeout_ms = 3000;
  return std::make_unique<fatek::Client>(fatek::tcp_transport("127.0.0.1:" + std::to_string(port)), o);
}

int fatek_port(Server& s) { return dynamic_cast<fatek::TcpServer&>(s).port(); }

// Blocks until the server closes a raw connection (read returns 0); false after 10 s.
bool closed_by_server(int fd) {
  pollfd p{fd, POLLIN, 0};
  if (::poll(&p, 1, 10000) <= 0) return false;
  char c;
  return ::recv(fd, &c, 1, 0) <= 0;
}

int connect_raw(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(uint16_t(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

}  // namespace

TEST(WritableRanges, ParsesAndChecksSpans) {
  const auto w = WritableRanges::parse("D0-D9, M800-M809,Y3");
  EXPECT_FALSE(w.everything());
  EXPECT_TRUE(w.allows(Area::D, 0, 10));
  EXPECT_FALSE(w.allows(Area::D, 5, 6));
  EXPECT_TRUE(w.allows(Area::Y, 3));
  EXPECT_FALSE(w.allows(Area::Y, 4));
  EXPECT_FALSE(w.allows(Area::R, 0));
  EXPECT_EQ(w.describe(), "D0-D9,M800-M809,Y3");
  EXPECT_TRUE(WritableRanges::parse("D0-D4 D5-D9").allows(Area::D, 0, 10));  // adjacent ranges join
  EXPECT_FALSE(WritableRanges::parse("none").allows(Area::D, 0));
  EXPECT_TRUE(WritableRanges::parse("all").everything());
  EXPECT_TRUE(WritableRanges().everything());
  EXPECT_THROW(WritableRanges::parse(""), Error);
  EXPECT_THROW(WritableRanges::parse("D9-D0"), Error);
  EXPECT_THROW(WritableRanges::parse("D0-R9"), Error);
  EXPECT_THROW(WritableRanges::parse("Q1"), Error);
}

TEST(NetworkDefaults, ServersBindLoopbackUnlessGivenAHost) {
  Plc plc;
  auto f = fatek::make_tcp_server(plc, ":0", 1);
  EXPECT_NE(f->describe().find("127.0.0.1:"), std::string::npos) << f->describe();
  modbus::SlaveOptions o;
  o.tcp = ":0";
  auto m = modbus::make_slave_servers(plc, o);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_NE(m[0]->describe().find("127.0.0.1:"), std::string::npos) << m[0]->describe();
  // Nothing configured, nothing served.
  EXPECT_TRUE(modbus::make_slave_servers(plc, modbus::SlaveOptions()).empty());
}

TEST(NetworkDefaults, FatekWritesOutsideTheRangesAreErrorAAndChangeNothing) {
  Plc plc;
  plc.load_program_text("ORG M1925\nOUT Y0\nEND\n", "t.il");
  fatek::ServerPolicy p;
  p.writable = WritableRanges::parse("D0-D9,Y5");
  auto s = fatek::make_tcp_server(plc, "127.0.0.1:0", 1, p);
  s->start();
  auto c = fatek_client(fatek_port(*s));
  c->write(at("D3"), {7});
  EXPECT_EQ(plc.read(at("D3"), 1)[0], 7u);
  const auto code_of = [](const std::function<void()>& fn) {
    try {
      fn();
    } catch (const fatek::PlcError& e) {
      return char(e.code);
    }
    return '0';
  };
  EXPECT_EQ(code_of([&] { c->write(at("D8"), {1, 2, 3}); }), 'A');  // D10 is outside
  EXPECT_EQ(code_of([&] { c->write(at("R0"), {1}); }), 'A');
  EXPECT_EQ(code_of([&] { c->write_mixed({at("D1"), at("R1")}, {5, 5}); }), 'A');
  EXPECT_EQ(code_of([&] { c->control(at("Y6"), fatek::Action::Set); }), 'A');
  EXPECT_EQ(code_of([&] { c->control(at("Y5"), fatek::Action::Set); }), '0');
  EXPECT_EQ(code_of([&] { c->set_run(true); }), '4');
  EXPECT_EQ(plc.read(at("D8"), 3), (std::vector<uint32_t>{0, 0, 0}));
  EXPECT_EQ(plc.read(at("R0"), 2), (std::vector<uint32_t>{0, 0}));
  EXPECT_EQ(plc.read(at("D1"), 1)[0], 0u);
  EXPECT_EQ(plc.read(at("Y6"), 1)[0], 0u);
  EXPECT_EQ(plc.mode(), RunMode::Stop);
  EXPECT_EQ(c->read(at("R0"), 1)[0], 0u);  // reads stay open
  s->stop();
}

TEST(NetworkDefaults, ModbusWritesOutsideTheRangesAreException02AndChangeNothing) {
  Plc plc;
  modbus::TcpServerOptions o;
  o.port = 0;
  o.writable = WritableRanges::parse("D0-D9,Y0-Y7");
  modbus::TcpServer s(plc, o);
  s.start();
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", s.bound_port());
  ASSERT_EQ(modbus_connect(ctx), 0);
  EXPECT_EQ(modbus_write_register(ctx, 6003, 9), 1);  // D3
  EXPECT_EQ(plc.read(at("D3"), 1)[0], 9u);
  const uint16_t regs[3] = {1, 2, 3};
  EXPECT_EQ(modbus_write_registers(ctx, 6008, 3, regs), -1);  // D8..D10
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(modbus_write_register(ctx, 0, 1), -1);  // R0
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(modbus_write_bit(ctx, 8, 1), -1);  // Y8
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(modbus_write_bit(ctx, 7, 1), 1);  // Y7
  EXPECT_EQ(plc.read(at("D8"), 3), (std::vector<uint32_t>{0, 0, 0}));
  EXPECT_EQ(plc.read(at("R0"), 1)[0], 0u);
  EXPECT_EQ(plc.read(at("Y8"), 1)[0], 0u);
  EXPECT_EQ(plc.read(at("Y7"), 1)[0], 1u);
  uint16_t v;
  EXPECT_EQ(modbus_read_registers(ctx, 0, 1, &v), 1);  // reads stay open
  modbus_close(ctx);
  modbus_free(ctx);
  s.stop();
}

TEST(NetworkDefaults, FatekConnectionCapAndIdleTimeoutAreConfigurable) {
  Plc plc;
  fatek::ServerPolicy p;
  p.max_connections = 1;
  p.idle_timeout_ms = 200;
  auto s = fatek::make_tcp_server(plc, "127.0.0.1:0", 1, p);
  s->start();
  const int port = fatek_port(*s);
  auto c = fatek_client(port);
  c->write(at("D0"), {1});  // the one allowed connection is open and served
  const int extra = connect_raw(port);
  ASSERT_GE(extra, 0);
  EXPECT_TRUE(closed_by_server(extra));  // over the cap: closed at once
  ::close(extra);
  EXPECT_EQ(c->read(at("D0"), 1)[0], 1u);  // the first is untouched
  c.reset();
  const int idle = connect_raw(port);
  ASSERT_GE(idle, 0);
  EXPECT_TRUE(closed_by_server(idle));  // silent: closed after the idle timeout
  ::close(idle);
  EXPECT_THROW(fatek::make_tcp_server(plc, ":0", 1, fatek::ServerPolicy{{}, 0, 1000}), Error);
  s->stop();
}

TEST(NetworkDefaults, ModbusConnectionCapIsConfigurable) {
  Plc plc;
  modbus::SlaveOptions o;
  o.tcp = "127.0.0.1:0";
  o.max_connections = 1;
  o.idle_timeout_ms = 200;
  auto servers = modbus::make_slave_servers(plc, o);
  servers[0]->start();
  const int port = dynamic_cast<modbus::TcpServer&>(*servers[0]).bound_port();
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", port);
  ASSERT_EQ(modbus_connect(ctx), 0);
  uint16_t v;
  EXPECT_EQ(modbus_read_registers(ctx, 0, 1, &v), 1);
  const int extra = connect_raw(port);
  ASSERT_GE(extra, 0);
  EXPECT_TRUE(closed_by_server(extra));
  ::close(extra);
  EXPECT_EQ(modbus_read_registers(ctx, 0, 1, &v), 1);
  modbus_close(ctx);
  modbus_free(ctx);
  const int idle = connect_raw(port);
  ASSERT_GE(idle, 0);
  EXPECT_TRUE(closed_by_server(idle));
  ::close(idle);
  o.max_connections = 0;
  EXPECT_THROW(modbus::make_slave_servers(plc, o), Error);
  servers[0]->stop();
}
