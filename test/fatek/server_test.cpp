// Client against server over TCP loopback (ephemeral port) and over a socat pty pair:
// every command, broadcast, forcing, RUN/STOP, the error codes the soft PLC produces,
// rejected frames that change nothing, and clients that stall or vanish mid-frame.
#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <regex>
#include <sstream>
#include <cstdlib>
#include <thread>

#include "fatek_link.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/client.h"
#include "plc_cell/fatek/server.h"
#include "plc_cell/io/serial_line.h"

using namespace plc_cell;
using namespace plc_cell::fatek;
using fatek_test::connect_local;
using fatek_test::roundtrip;

namespace {

const char* kProgram = "ORG X0\nOUT Y0\nEND\n";

std::string frame(const std::string& body) {
  std::string s = "\x02" + body;
  append_hex(s, lrc(s), 2);
  s.push_back('\x03');
  return s;
}

class FatekTcp : public ::testing::Test {
 protected:
  void SetUp() override {
    plc.load_program_text(kProgram, "t.il");
    TcpServerOptions o;
    o.port = 0;  // ephemeral
    o.station = 1;
    o.frame_timeout_ms = 300;
    server = std::make_unique<TcpServer>(plc, o);
    server->start();
    port = server->port();
    ASSERT_GT(port, 0);
    client = make_client(1);
  }
  void TearDown() override { server->stop(); }
  std::unique_ptr<Client> make_client(int station, int timeout_ms = 3000) {
    ClientOptions co;
    co.station = station;
    co.timeout_ms = timeout_ms;
    co.retries = 0;
    return std::make_unique<Client>(tcp_transport("127.0.0.1:" + std::to_string(port)), co);
  }
  uint32_t mem(const std::string& a) { return plc.read(parse_address(a), 1)[0]; }

  Plc plc;
  std::unique_ptr<TcpServer> server;
  std::unique_ptr<Client> client;
  int port = 0;
};

ErrorCode plc_error(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const PlcError& e) {
    return e.code;
  }
  return ErrorCode::Ok;
}

}  // namespace

TEST_F(FatekTcp, StatusRunStopReportsTheEngine) {
  EXPECT_FALSE(client->status().run);
  client->set_run(true);
  EXPECT_EQ(plc.mode(), RunMode::Run);
  EXPECT_TRUE(client->status().run);
  const PlcStatus d = client->detailed_status();
  EXPECT_TRUE(d.run);
  ASSERT_EQ(d.bytes.size(), kDetailedStatusBytes);
  EXPECT_EQ(d.bytes[20], 0x1F);  // R registers: 8072 = 1F88H
  EXPECT_EQ(d.bytes[21], 0x88);
  client->set_run(false);
  EXPECT_EQ(plc.mode(), RunMode::Stop);
  EXPECT_FALSE(client->status().run);
}

TEST_F(FatekTcp, RunWithoutProgramIsError5) {
  Plc empty;
  TcpServerOptions o;
  o.port = 0;
  TcpServer s(empty, o);
  s.start();
  ClientOptions co;
  co.timeout_ms = 3000;
  Client c(tcp_transport("127.0.0.1:" + std::to_string(s.port())), co);
  EXPECT_EQ(c.status().status1 & kStatusLadderChecksum, kStatusLadderChecksum);
  EXPECT_EQ(plc_error([&] { c.set_run(true); }), ErrorCode::LadderChecksum);
  EXPECT_EQ(empty.mode(), RunMode::Stop);
}

TEST_F(FatekTcp, ReadWriteRegistersAndDiscretes) {
  plc.write(parse_address("R12"), {0x10A5, 0x7FC4, 1});
  EXPECT_EQ(client->read(parse_address("R12"), 3), (std::vector<uint32_t>{0x10A5, 0x7FC4, 1}));
  client->write(parse_address("D10"), {1, 2, 3});
  EXPECT_EQ(plc.read(parse_address("D10"), 3), (std::vector<uint32_t>{1, 2, 3}));
  client->write(parse_address("DR100"), {0x12345678});
  EXPECT_EQ(mem("R100"), 0x5678u);  // low word at the lower address
  EXPECT_EQ(mem("R101"), 0x1234u);
  EXPECT_EQ(client->read(parse_address("DR100"), 1)[0], 0x12345678u);
  client->write(parse_address("Y0"), {1, 0, 0, 1});
  EXPECT_EQ(plc.read(parse_address("Y0"), 4), (std::vector<uint32_t>{1, 0, 0, 1}));
  EXPECT_EQ(client->read(parse_address("WY0"), 1)[0], 0x9u);
  client->write(parse_address("WM16"), {0xAAAA});
  EXPECT_EQ(mem("M17"), 1u);
  EXPECT_EQ(mem("M16"), 0u);
  // Larger than one frame: split into 64-word and 256-discrete frames.
  std::vector<uint32_t> v(300);
  for (uint32_t i = 0; i < v.size(); ++i) v[i] = i * 7;
  client->write(parse_address("R1000"), v);
  EXPECT_EQ(plc.read(parse_address("R1000"), 300), v);
  EXPECT_EQ(client->read(parse_address("R1000"), 300), v);
  std::vector<uint32_t> bits(600);
  for (uint32_t i = 0; i < bits.size(); ++i) bits[i] = (i % 3) == 0;
  client->write(parse_address("M100"), bits);
  EXPECT_EQ(client->read(parse_address("M100"), 600), bits);
}

TEST_F(FatekTcp, MixedReadWrite) {
  client->write_mixed({parse_address("Y0"), parse_address("WY8"), parse_address("DF2"), parse_address("R1")},
                      {1, 0x5555, 0xFF, 0x5C34});
  EXPECT_EQ(mem("Y0"), 1u);
  EXPECT_EQ(mem("WY8"), 0x5555u);
  EXPECT_EQ(mem("DF2"), 0xFFu);
  EXPECT_EQ(client->read_mixed({parse_address("R1"), parse_address("Y0"), parse_address("DF2")}),
            (std::vector<uint32_t>{0x5C34, 1, 0xFF}));
  // 40 DW = weight 80 > 64: split into two frames by the client.
  std::vector<Address> pts;
  std::vector<uint32_t> vals;
  for (uint32_t i = 0; i < 40; ++i) {
    pts.push_back(parse_address("DD" + std::to_string(2 * i)));
    vals.push_back(0x10000u + i);
  }
  client->write_mixed(pts, vals);
  EXPECT_EQ(client->read_mixed(pts), vals);
}

TEST_F(FatekTcp, ForcingDisablesAndSets) {
  client->control(parse_address("Y5"), Action::Disable);
  EXPECT_TRUE(plc.locked([](ScanEngine&, Memory& m) { return m.disabled(Area::Y, 5); }));
  EXPECT_EQ(client->read_disabled(parse_address("Y4"), 3), (std::vector<bool>{false, true, false}));
  client->write(parse_address("Y5"), {1});  // a disabled point ignores ordinary writes
  EXPECT_EQ(mem("Y5"), 0u);
  client->control(parse_address("Y5"), Action::Set);  // but SET forces it
  EXPECT_EQ(mem("Y5"), 1u);
  client->control(parse_address("Y5"), Action::Reset);
  EXPECT_EQ(mem("Y5"), 0u);
  client->control(parse_address("Y5"), Action::Enable);
  EXPECT_EQ(client->read_disabled(parse_address("Y5"), 1), (std::vector<bool>{false}));
  // A disabled input keeps its forced level through scans.
  plc.set_mode(RunMode::Run);
  client->control(parse_address("X0"), Action::Disable);
  client->control(parse_address("X0"), Action::Set);
  plc.set_input(0, false);
  plc.scan(1000);
  plc.scan(2000);
  EXPECT_EQ(mem("X0"), 1u);
  EXPECT_EQ(mem("Y0"), 1u);  // the program saw the forced input
}

TEST_F(FatekTcp, ErrorCodesFromTheServer) {
  const int fd = connect_local(port);
  // 2: illegal value (65 words; discrete value not 0/1; RUN code 2).
  EXPECT_EQ(roundtrip(fd, frame("014641R00000")), frame("01462"));
  EXPECT_EQ(roundtrip(fd, frame("014501Y00002")), frame("01452"));
  EXPECT_EQ(roundtrip(fd, frame("01412")), frame("01412"));
  // 4: illegal format / unknown command.
  EXPECT_EQ(roundtrip(fd, frame("0150")), frame("01504"));
  EXPECT_EQ(roundtrip(fd, frame("014603Q00012")), frame("01464"));
  // A: illegal address.
  EXPECT_EQ(roundtrip(fd, frame("014601R09000")), frame("0146A"));
  EXPECT_EQ(roundtrip(fd, frame("01423X0300")), frame("0142A"));
  ::close(fd);
}

// The request class -> answer table of docs/fatek.md, read from the page.
TEST_F(FatekTcp, TableInTheDocs) {
  std::ifstream in(std::string(PLC_CELL_SOURCE_DIR) + "/docs/fatek.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  const auto b = doc.find("<!-- fatek-request-classes: begin -->"), e = doc.find("<!-- fatek-request-classes: end -->");
  ASSERT_NE(b, std::string::npos);
  ASSERT_NE(e, std::string::npos);
  std::istringstream lines(doc.substr(b, e - b));
  const std::regex row(R"(^\| ([^|]+) \| `([0-9A-Z]+)` \| ([0-9A]|none) \|$)");
  const int fd = connect_local(port);
  int rows = 0;
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("| ", 0) != 0 || line.find('`') == std::string::npos) continue;
    std::smatch m;
    ASSERT_TRUE(std::regex_match(line, m, row)) << "unreadable row: " << line;
    ++rows;
    const std::string req = m[2], want = m[3];
    const std::string got = roundtrip(fd, frame(req), want == "none" ? 300 : 3000);
    if (want == "none") {
      EXPECT_EQ(got, "") << m[1];
      continue;
    }
    ASSERT_GE(got.size(), 6u) << m[1] << ": no answer";
    EXPECT_EQ(got.substr(1, 4), "01" + req.substr(2, 2)) << m[1];
    EXPECT_EQ(got[5], want[0]) << m[1] << ": " << got;
  }
  EXPECT_GE(rows, 15);
  // Still in step after the refused requests.
  EXPECT_EQ(roundtrip(fd, frame("0140")).substr(5, 1), "0");
  ::close(fd);
}

TEST(FatekClientErrors, EveryErrorCodeBecomesPlcError) {
  // A one-shot fake slave answers each error code; the client reports it, without retrying.
  for (char code : std::string("245679A")) {
    const int ls = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in sa{};
    sa.sin_family = AF_INET;
    sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(::bind(ls, reinterpret_cast<sockaddr*>(&sa), sizeof sa), 0);
    ::listen(ls, 1);
    socklen_t len = sizeof sa;
    getsockname(ls, reinterpret_cast<sockaddr*>(&sa), &len);
    std::thread fake([&] {
      const int c = ::accept(ls, nullptr, nullptr);
      char buf[64];
      (void)!::recv(c, buf, sizeof buf, 0);
      const std::string rsp = frame(std::string("0141") + code);
      (void)!::send(c, rsp.data(), rsp.size(), MSG_NOSIGNAL);
      ::recv(c, buf, sizeof buf, 0);  // until the client closes
      ::close(c);
    });
    {
      ClientOptions co;
      co.timeout_ms = 3000;
      Client c(tcp_transport("127.0.0.1:" + std::to_string(ntohs(sa.sin_port))), co);
      EXPECT_EQ(plc_error([&] { c.set_run(true); }), ErrorCode(code)) << code;
      EXPECT_EQ(c.retries_used(), 0u);
    }
    fake.join();
    ::close(ls);
  }
}

TEST_F(FatekTcp, BroadcastExecutesWritesWithoutReply) {
  client->set_station(0);
  client->write(parse_address("R100"), {7});
  client->control(parse_address("Y7"), Action::Set);
  EXPECT_THROW(client->read(parse_address("R100"), 1), Error);  // a broadcast read has no answer
  client->set_station(1);
  EXPECT_EQ(client->read(parse_address("R100"), 1)[0], 7u);  // same stream: processed in order
  EXPECT_EQ(mem("Y7"), 1u);
  // And the broadcast produced no bytes: the next answer on a raw socket is the read's.
  const int fd = connect_local(port);
  const std::string none = roundtrip(fd, frame("004701R001000009"), 200);
  EXPECT_EQ(none, "");
  EXPECT_EQ(roundtrip(fd, frame("014601R00100")), frame("014600009"));
  ::close(fd);
}

TEST_F(FatekTcp, OtherStationsAreIgnored) {
  auto other = make_client(2, 200);
  EXPECT_THROW(other->status(), CommError);
  EXPECT_EQ(client->loopback("ABCDEFG"), "ABCDEFG");
}

TEST_F(FatekTcp, RejectedFramesChangeNothing) {
  plc.write(parse_address("R0"), {11, 22});
  plc.write(parse_address("Y3"), {1});
  const int fd = connect_local(port);
  // Bad LRC: dropped silently.
  std::string bad = frame("014702R0000000010002");
  bad[bad.size() - 2] ^= 1;
  EXPECT_EQ(roundtrip(fd, bad, 200), "");
  // Truncated (ETX missing, then a new STX resyncs).
  EXPECT_EQ(roundtrip(fd, std::string("\x02") + "014702R00000000", 200), "");
  // Mixed write whose second item is out of range: refused whole, first item untouched.
  EXPECT_EQ(roundtrip(fd, frame("014902R000000063Y03000")), frame("0149A"));
  EXPECT_EQ(roundtrip(fd, frame("014902Y00030R0900000AA")), frame("0149A"));
  // Continuous write running past the end of R.
  EXPECT_EQ(roundtrip(fd, frame("014702R0807100010002")), frame("0147A"));
  EXPECT_EQ(mem("R0"), 11u);
  EXPECT_EQ(mem("R1"), 22u);
  EXPECT_EQ(mem("Y3"), 1u);
  EXPECT_EQ(mem("R8071"), 0u);
  // Still answering.
  EXPECT_EQ(roundtrip(fd, frame("014602R00000")), frame("01460000B0016"));
  ::close(fd);
  EXPECT_GE(server->status().rejected, 4u);
}

TEST_F(FatekTcp, StalledAndVanishingClientsDoNotHoldUpOthers) {
  // One client stalls mid-frame, one sends garbage, one disconnects mid-frame.
  const int stall = connect_local(port);
  ASSERT_EQ(::send(stall, "\x02" "0146", 5, 0), 5);
  const int junk = connect_local(port);
  const std::string garbage(2000, '\x7F');
  ASSERT_EQ(::send(junk, garbage.data(), garbage.size(), 0), ssize_t(garbage.size()));
  {
    const int gone = connect_local(port);
    ASSERT_EQ(::send(gone, "\x02" "0147", 5, 0), 5);
    ::close(gone);
  }
  plc.write(parse_address("R5"), {55});
  for (int i = 0; i < 20; ++i) EXPECT_EQ(client->read(parse_address("R5"), 1)[0], 55u);
  // The stalled client's partial frame is dropped after the frame timeout; it can then talk.
  EXPECT_EQ(roundtrip(stall, frame("014601R00005"), 3000), frame("014600037"));
  ::close(stall);
  ::close(junk);
}

TEST_F(FatekTcp, ConnectionCountIsBounded) {
  std::vector<int> fds;
  for (int i = 0; i < 7; ++i) fds.push_back(connect_local(port));  // + the fixture's client = 8
  EXPECT_EQ(client->loopback("A"), "A");
  const int extra = connect_local(port);  // the 9th is accepted and closed at once
  char c;
  ASSERT_TRUE(wait_readable(extra, 3000));
  EXPECT_EQ(::recv(extra, &c, 1, 0), 0);
  ::close(extra);
  for (int fd : fds) ::close(fd);
  EXPECT_EQ(client->loopback("B"), "B");
}

TEST(FatekSerial, ClientAndServerOverAPtyPair) {
  fatek_test::TempDir dir;
  {
    fatek_test::PtyPair pty(dir.path);
    Plc plc;
    plc.load_program_text(kProgram, "t.il");
    SerialServerOptions so;
    so.line = parse_serial_settings(pty.a + ":921600:7E1");
    so.station = 3;
    SerialServer server(plc, so);
    server.start();
    ClientOptions co;
    co.station = 3;
    co.timeout_ms = 3000;
    co.retries = 0;
    Client c(serial_transport(parse_serial_settings(pty.b + ":921600:7E1")), co);
    EXPECT_EQ(c.loopback("HELLO"), "HELLO");
    c.set_run(true);
    EXPECT_TRUE(c.status().run);
    c.write(parse_address("R10"), {1, 2, 3});
    EXPECT_EQ(plc.read(parse_address("R10"), 3), (std::vector<uint32_t>{1, 2, 3}));
    EXPECT_EQ(c.read(parse_address("R10"), 3), (std::vector<uint32_t>{1, 2, 3}));
    c.control(parse_address("M7"), Action::Disable);
    EXPECT_EQ(c.read_disabled(parse_address("M7"), 1), (std::vector<bool>{true}));
    plc.write(parse_address("D4095"), {0xBEEF});
    EXPECT_EQ(c.read_mixed({parse_address("D4095"), parse_address("M7")}), (std::vector<uint32_t>{0xBEEF, 0}));
    EXPECT_THROW(c.read(parse_address("R8071"), 2), Error);  // refused before sending
    // Broadcast over the line, then a read proves it was executed and unanswered.
    c.set_station(0);
    c.write(parse_address("D5"), {99});
    c.set_station(3);
    EXPECT_EQ(c.read(parse_address("D5"), 1)[0], 99u);
    c.set_run(false);
    EXPECT_FALSE(c.status().run);
    // Garbage on the line, then a frame cut short: the next request is still answered.
    const int fd = open_serial_line(parse_serial_settings(pty.b + ":921600:7E1"));
    ASSERT_TRUE(write_all(fd, "\x7fnoise\x02" "0346", 11, 1000));
    ::close(fd);
    EXPECT_EQ(c.read(parse_address("R11"), 1)[0], 2u);
    server.stop();
  }
}

TEST_F(FatekTcp, SeveralClientsAtOnce) {
  // Four clients hammer the server concurrently, each on its own registers.
  std::vector<std::thread> threads;
  std::atomic<int> bad{0};
  for (int k = 0; k < 4; ++k) {
    threads.emplace_back([&, k] {
      auto c = make_client(1);
      const Address base{Area::D, Width::Word, uint32_t(100 * k)};
      for (uint32_t i = 0; i < 200; ++i) {
        std::vector<uint32_t> v(10, (uint32_t(k) << 12) | i);
        c->write(base, v);
        if (c->read(base, 10) != v) ++bad;
      }
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(bad.load(), 0);
  for (int k = 0; k < 4; ++k)
    EXPECT_EQ(plc.read(Address{Area::D, Width::Word, uint32_t(100 * k)}, 1)[0], (uint32_t(k) << 12) | 199u);
}

TEST(FatekSerial, EveryLineFormatOpensAndTalks) {
  // On a pty the line format cannot be enforced (docs/fatek.md); what matters is that each
  // format parses, opens and carries FATEK frames unchanged.
  fatek_test::TempDir dir;
  fatek_test::PtyPair pty(dir.path);
  for (const char* fmt : {"7E1", "8N1", "8E1", "7O1", "8N2"}) {
    Plc plc;
    SerialServerOptions so;
    so.line = parse_serial_settings(pty.a + ":4800:" + fmt);
    SerialServer server(plc, so);
    server.start();
    ClientOptions co;
    co.timeout_ms = 3000;
    co.retries = 0;
    Client c(serial_transport(parse_serial_settings(pty.b + ":4800:" + fmt)), co);
    EXPECT_EQ(c.loopback(fmt), fmt);
    server.stop();
  }
  EXPECT_THROW(open_serial_line(parse_serial_settings(pty.a + ":1234:7E1")), Error);  // no such baud
}

TEST(FatekTcpIdle, ClientReconnectsAfterTheServerClosedAnIdleConnection) {
  Plc plc;
  TcpServerOptions o;
  o.port = 0;
  o.idle_timeout_ms = 1;  // the server drops a connection as soon as it is quiet
  TcpServer s(plc, o);
  s.start();
  ClientOptions co;
  co.timeout_ms = 3000;
  co.retries = 0;  // no retry needed: the client notices the closed connection itself
  Client c(tcp_transport("127.0.0.1:" + std::to_string(s.port())), co);
  EXPECT_EQ(c.loopback("A"), "A");
  // Block until the server has closed our connection: the socket then reads EOF.
  Client probe(tcp_transport("127.0.0.1:" + std::to_string(s.port())), co);
  char buf[8];
  EXPECT_THROW(
      {
        probe.transport().open();
        while (probe.transport().recv(buf, sizeof buf, 3000) == 0) {
        }
      },
      CommError);
  // c's connection was idle as long: closed too. The next request still succeeds.
  for (int i = 0; i < 3; ++i) EXPECT_EQ(c.loopback("B"), "B");
}
