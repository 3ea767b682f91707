// The host-link servers: TCP loopback (ephemeral port) and a socat pty pair, with the
// manual's vectors, the Ctrl-E handshake, frames split across reads, and the server kind.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <termios.h>

#include "../fatek/fatek_link.h"
#include "plc_cell/config/cell_config.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/serial_port.h"
#include "plc_cell/tri/server.h"
#include "plc_cell/tri/server_kind.h"

using namespace plc_cell;
using namespace plc_cell::tri;
using fatek_test::connect_local;

namespace {

// Reads until the reply is whole: a CR, or the lone Ctrl-E echo. "" on timeout.
std::string read_reply(int fd, int timeout_ms = 3000) {
  std::string got;
  char buf[256];
  while (fatek::wait_readable(fd, timeout_ms)) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) break;
    got.append(buf, size_t(n));
    if (got.back() == '\r' || got == "\x05") return got;
  }
  return got;
}

// A multi-point frame with its own FCS.
std::string mp(int id, const std::string& body) {
  Frame f;
  f.multipoint = true;
  f.id = id;
  f.body = body;
  return encode_frame(f);
}

std::string talk(int fd, const std::string& bytes) {
  if (::write(fd, bytes.data(), bytes.size()) != ssize_t(bytes.size())) return "";
  return read_reply(fd);
}

class TriTcp : public ::testing::Test {
 protected:
  void SetUp() override {
    ServerOptions o;
    o.frame_timeout_ms = 300;
    server = std::make_unique<TcpServer>(plc, "127.0.0.1", 0, o);
    server->start();
    fd = connect_local(server->port());
  }
  void TearDown() override {
    ::close(fd);
    server->stop();
  }
  Plc plc;
  std::unique_ptr<TcpServer> server;
  int fd = -1;
};

}  // namespace

TEST_F(TriTcp, ManualVectorsOverLoopback) {
  plc.write(parse_address("D3599"), {12345});
  EXPECT_EQ(talk(fd, "\x05"), "\x05");  // the point-to-point handshake
  EXPECT_EQ(talk(fd, "RVD0E10*\r"), "RVD3039*\r");
  EXPECT_EQ(talk(fd, "WVD03E804D2*\r"), "WVD*\r");
  EXPECT_EQ(plc.read(parse_address("D999"), 1)[0], 1234u);
  EXPECT_EQ(talk(fd, "@01RI0258*\r"), mp(1, "RI00"));
  EXPECT_EQ(talk(fd, "IR*\r"), "IR01*\r");
  EXPECT_EQ(talk(fd, "wb0100FF*\r"), "wb*\r");
  EXPECT_EQ(plc.read(parse_address("Y0"), 1)[0], 1u);
  // A frame in pieces, then two frames in one write.
  ASSERT_EQ(::write(fd, "RV", 2), 2);
  ASSERT_EQ(::write(fd, "D0E", 3), 3);
  EXPECT_EQ(talk(fd, "10*\r"), "RVD3039*\r");
  std::string two = talk(fd, "IR*\rRVD03E8*\r");
  if (two.find("RVD") == std::string::npos) two += read_reply(fd);
  EXPECT_EQ(two, "IR01*\rRVD04D2*\r");
  EXPECT_GE(server->status().requests, 7u);
  EXPECT_EQ(server->describe(), "TRi TCP 127.0.0.1:" + std::to_string(server->port()) + " ID 01");
}

TEST_F(TriTcp, OtherIdsAndGarbageGetNoReply) {
  // Another PLC's frame and a line without '*': nothing comes back; the next frame is answered.
  const std::string silent = mp(2, "IR") + "\x01\x02junk\r";
  ASSERT_EQ(::write(fd, silent.data(), silent.size()), ssize_t(silent.size()));
  EXPECT_EQ(talk(fd, mp(1, "IR")), mp(1, "IR01"));
}

TEST(TriSerial, ManualVectorsOverAPtyPair) {
  fatek_test::TempDir dir;
  fatek_test::PtyPair pty(dir.path);
  Plc plc;
  plc.write(parse_address("DR3780"), {123456});
  SerialSettings line;
  line.device = pty.a;
  line.baud = 38400;
  line.data_bits = 8;
  line.parity = 'N';
  SerialServer server(plc, line, ServerOptions{});
  server.start();
  const int fd = ::open(pty.b.c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(fd, 0);
  termios t{};
  ASSERT_EQ(::tcgetattr(fd, &t), 0);
  ::cfmakeraw(&t);
  ASSERT_EQ(::tcsetattr(fd, TCSANOW, &t), 0);
  EXPECT_EQ(talk(fd, "\x05"), "\x05");
  EXPECT_EQ(talk(fd, "RVIK*\r"), "RVI0001E240*\r");
  EXPECT_EQ(talk(fd, "@04RVIA48*\r@01RVIA00*\r"), mp(1, "RVI00000000"));
  EXPECT_EQ(talk(fd, "WVS0801000E*\r"), "WVS*\r");
  EXPECT_EQ(plc.read(parse_address("R4130"), 1)[0], 14u);
  EXPECT_EQ(server.describe(), "TRi serial " + pty.a + ":38400:8N1 ID 01");
  ::close(fd);
  server.stop();
}

TEST(TriServerKind, DefaultsAndServers) {
  const ServerKind k = server_kind();
  EXPECT_EQ(k.name, "tri");
  ASSERT_NE(k.spec("id"), nullptr);
  EXPECT_EQ(k.spec("id")->fallback, "1");
  EXPECT_EQ(k.option(*k.spec("tcp")), "--tri-tcp");
  EXPECT_EQ(k.parameter(*k.spec("tcp")), "~tri_tcp");
  CellConfig cfg;
  auto settings = merge_server_settings({k}, cfg,
                                        {{"tri", "tcp", {"127.0.0.1:0"}, "--tri-tcp"},
                                         {"tri", "serial", {"/dev/null-tri"}, "--tri-serial"},
                                         {"tri", "id", {"10"}, "--tri-id"}});
  Plc plc;
  auto servers = k.make(plc, settings.at("tri"));
  ASSERT_EQ(servers.size(), 2u);
  EXPECT_EQ(servers[0]->describe(), "TRi TCP 127.0.0.1:0 ID 0A");
  EXPECT_EQ(servers[1]->describe(), "TRi serial /dev/null-tri:38400:8N1 ID 0A");  // the TRi's default line
  EXPECT_THROW(merge_server_settings({k}, cfg, {{"tri", "id", {"256"}, "--tri-id"}}), std::exception);
}

TEST(TriServerKind, CellYaml) {
  const ServerKind k = server_kind();
  const CellConfig cfg = parse_cell_config(
      "cell: {program: p.il}\nservers:\n  tri: {tcp: '127.0.0.1:0', id: 4, wildcard_fcs: 0, writable: [D0-D9]}\n",
      "cell.yaml", {"servers"});
  auto settings = merge_server_settings({k}, cfg);
  Plc plc;
  auto servers = k.make(plc, settings.at("tri"));
  ASSERT_EQ(servers.size(), 1u);
  auto* tcp = dynamic_cast<TcpServer*>(servers[0].get());
  ASSERT_NE(tcp, nullptr);
  tcp->start();
  const int fd = connect_local(tcp->port());
  EXPECT_EQ(talk(fd, "@04RVD000100*\r"), mp(4, "FE"));  // the wildcard refused
  EXPECT_EQ(talk(fd, mp(4, "WVD000B0001")), mp(4, "ER04"));  // DM[11] = D10: not writable
  EXPECT_EQ(talk(fd, mp(4, "WVD000A0001")), mp(4, "WVD"));
  ::close(fd);
  tcp->stop();
  // An unknown key is refused with the list of known ones.
  const CellConfig bad = parse_cell_config("cell: {program: p.il}\nservers:\n  tri: {port: 9080}\n", "cell.yaml",
                                           {"servers"});
  EXPECT_THROW(merge_server_settings({k}, bad), std::exception);
}
