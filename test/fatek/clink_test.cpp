// FUN151 CLINK MD0: a master soft PLC runs a link table against a slave soft PLC over TCP.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <thread>

#include "plc_cell/core/error.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/clink.h"
#include "plc_cell/io/serial_line.h"
#include "../reliability/pty_proxy.h"
#include "fatek_link.h"
#include "plc_cell/io/com_port.h"
#include "plc_cell/fatek/serial_port.h"
#include "plc_cell/fatek/server.h"

using namespace plc_cell;
using namespace plc_cell::fatek;

namespace {

const char* kMaster =
    "ORG M0\nLD M1\nLD M2\nFUN 151 Pt=1 MD=0 SR=R100 WR=R200 ACT=Y0 ERR=Y1 DN=Y2\nEND\n";

class Clink : public ::testing::Test {
 protected:
  void SetUp() override {
    TcpServerOptions o;
    o.port = 0;
    o.station = 5;
    server = std::make_unique<TcpServer>(slave, o);
    server->start();
    auto ports = std::make_shared<ClinkPorts>();
    ports->set_port(1, tcp_transport("127.0.0.1:" + std::to_string(server->port())), 300);
    FunctionTable t = FunctionTable::with_core_functions();
    add_clink_function(t, ports);
    master = std::make_unique<Plc>(std::move(t));
    master->load_program_text(kMaster, "master.il");
    ASSERT_TRUE(master->set_mode(RunMode::Run));
  }
  void TearDown() override { server->stop(); }
  void table(std::vector<uint32_t> words) { master->write(parse_address("R100"), words); }
  uint32_t m(const std::string& a) { return master->read(parse_address(a), 1)[0]; }
  uint32_t s(const std::string& a) { return slave.read(parse_address(a), 1)[0]; }
  // Scans until pred holds (the line works on its own thread); no sleeping, bounded by a deadline.
  bool scan_until(const std::function<bool()>& pred) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < deadline) {
      master->scan(now += 1000);
      if (pred()) return true;
      std::this_thread::yield();
    }
    return false;
  }
  // Scans until the DN pulse of one finished packet; returns WR+0.
  uint32_t next_packet() {
    EXPECT_TRUE(scan_until([&] { return m("Y2") == 1; }));
    return m("R200");
  }

  Plc slave;
  std::unique_ptr<TcpServer> server;
  std::unique_ptr<Plc> master;
  uint64_t now = 0;
};

}  // namespace

TEST_F(Clink, ReadsAndWritesSlaveDataByTable) {
  slave.write(parse_address("R0"), {11, 22, 33, 44});
  master->write(parse_address("Y8"), {1, 0, 1});
  // 2 transactions: read slave R0..R3 into master R10..R13; write master Y8..Y10 to slave M20..M22.
  table({2, 5, 1, 4, 12, 10, 12, 0, 5, 2, 3, 1, 8, 2, 20});
  EXPECT_EQ(m("M1960"), 0u);  // cleared on RUN; the instruction maintains it from the first scan
  master->write(parse_address("M0"), {1});
  EXPECT_EQ(next_packet(), 0x0000u);  // result 0, transaction 0
  EXPECT_EQ(m("R201"), 0x0546u);      // station 5, command 46H
  EXPECT_EQ(master->read(parse_address("R10"), 4), (std::vector<uint32_t>{11, 22, 33, 44}));
  EXPECT_EQ(m("Y1"), 0u);
  EXPECT_EQ(next_packet(), 0x0001u);  // transaction 1 done
  EXPECT_EQ(m("R201"), 0x0545u);      // write discretes
  EXPECT_EQ(slave.read(parse_address("M20"), 3), (std::vector<uint32_t>{1, 0, 1}));
  EXPECT_EQ(m("M1961"), 1u);  // port finished after the last packet
  // EN off: the port is released between transactions.
  master->write(parse_address("M0"), {0});
  EXPECT_TRUE(scan_until([&] { return m("Y0") == 0 && m("M1960") == 1; }));
}

TEST_F(Clink, TableErrorsAndTimeoutGiveResultCodes) {
  // Packet 0: length 0 -> 2; packet 1: command 3 -> 3; packet 2: type 14 -> 4;
  // packet 3: R5000 master ref -> 5; packet 4: bit vs word -> 6; packet 5: station 9 -> A.
  table({6, 5, 1, 0, 12, 0, 12, 0, 5, 3, 1, 12, 0, 12, 0, 5, 1, 1, 14, 0, 12, 0, 5, 1, 1, 12, 5000, 12, 0,
         5, 1, 1, 2, 0, 12, 0, 9, 1, 1, 12, 0, 12, 0});
  master->write(parse_address("M0"), {1});
  const uint32_t expect[] = {0x0200, 0x0301, 0x0402, 0x0503, 0x0604, 0x0A05};
  for (uint32_t e : expect) {
    EXPECT_EQ(next_packet(), e);
    EXPECT_EQ(m("Y1"), 1u);  // ERR with DN
  }
}

TEST_F(Clink, AbortRestartsFromTheFirstPacket) {
  slave.write(parse_address("R0"), {7});
  table({2, 5, 1, 1, 12, 10, 12, 0, 5, 1, 1, 12, 11, 12, 0});
  master->write(parse_address("M0"), {1});
  EXPECT_EQ(next_packet(), 0x0000u);
  master->write(parse_address("M2"), {1});  // ABT
  master->scan(now += 1000);
  EXPECT_EQ(m("Y0"), 0u);  // port released
  EXPECT_EQ(m("M1960"), 1u);
  master->write(parse_address("M2"), {0});
  master->write(parse_address("M0"), {0});
  master->scan(now += 1000);
  master->write(parse_address("M0"), {1});  // a new rising edge starts at packet 0 again
  EXPECT_EQ(next_packet(), 0x0000u);
}

TEST(ClinkConfig, PortsFromTheCellYaml) {
  const YAML::Node f = YAML::Load("ports: {2: 'tcp:127.0.0.1:1'}\ntimeout_ms: 100\n");
  auto ports = ClinkPorts::from_yaml(f, "cell.yaml");
  EXPECT_TRUE(ports->has(2));
  EXPECT_FALSE(ports->has(1));
  EXPECT_THROW(ClinkPorts::from_yaml(YAML::Load("ports: {7: 'tcp:127.0.0.1:1'}"), "cell.yaml"), Error);
}

// fatek: is read by the cell's YAML reader: every key and line is checked, and an error
// names file:line:column and the key (docs/fatek.md).
TEST(ClinkConfig, ErrorsNameFileLineAndKey) {
  const auto error = [](const std::string& yaml) {
    try {
      read_clink_settings(YAML::Load(yaml)["fatek"], "cell.yaml");
    } catch (const SourceError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("fatek:\n  timeout: 100\n"),
            "cell.yaml:2:3: error: key 'fatek.timeout': unknown key (expected one of: ports, timeout_ms)");
  EXPECT_EQ(error("fatek:\n  timeout_ms: 0\n"), "cell.yaml:2:15: error: key 'fatek.timeout_ms': value out of range [1, 60000]");
  EXPECT_EQ(error("fatek:\n  ports:\n    7: tcp:127.0.0.1:1\n"), "cell.yaml:3:5: error: key 'fatek.ports.7': FUN151 port 7 outside 1..4");
  EXPECT_EQ(error("fatek:\n  ports:\n    1: /dev/ttyS1:9600:7X1\n").rfind("cell.yaml:3:8: error: key 'fatek.ports.1': ", 0), 0u);
  EXPECT_EQ(error("fatek:\n  ports:\n    2: tcp:localhost\n").rfind("cell.yaml:3:8: error: key 'fatek.ports.2': ", 0), 0u);
  EXPECT_EQ(error("fatek:\n  ports: [tcp:127.0.0.1:1]\n").rfind("cell.yaml:2:10: error: key 'fatek.ports': expected a mapping", 0), 0u);
  // A good section reads as before.
  const ClinkSettings s = read_clink_settings(
      YAML::Load("fatek:\n  timeout_ms: 100\n  ports:\n    1: /dev/ttyS1:9600:7E1\n    2: tcp:127.0.0.1:500\n")["fatek"],
      "cell.yaml");
  EXPECT_EQ(s.timeout_ms, 100);
  EXPECT_EQ(s.ports, (std::map<int, std::string>{{1, "/dev/ttyS1:9600:7E1"}, {2, "tcp:127.0.0.1:500"}}));
  EXPECT_EQ(read_clink_settings(YAML::Load("cell: {}")["fatek"], "cell.yaml").timeout_ms, 500);
}

namespace {

// A master soft PLC whose port 2 is one end of a socat pty pair; the test plays the
// intelligent peripheral on the other end.
class ClinkFree : public ::testing::Test {
 protected:
  void SetUp() override {
    pty = std::make_unique<fatek_test::PtyPair>(dir.path);
    auto ports = std::make_shared<ClinkPorts>();
    ports->set_port(2, serial_transport(parse_serial_settings(pty->a + ":115200:8N1")), 300);
    FunctionTable t = FunctionTable::with_core_functions();
    add_clink_function(t, ports);
    master = std::make_unique<Plc>(std::move(t));
    master->load_program_text(
        "ORG M10\nLD M11\nLD M12\nFUN 151 Pt=2 MD=1 SR=R300 WR=R400 ACT=Y10 ERR=Y11 DN=Y12\n"
        "ORG M20\nLD M21\nLD M22\nFUN 151 Pt=2 MD=2 SR=R500 WR=R600 ACT=Y20 ERR=Y21 DN=Y22\nEND\n",
        "free.il");
    ASSERT_TRUE(master->set_mode(RunMode::Run));
    peer = open_serial_line(parse_serial_settings(pty->b + ":115200:8N1"));
  }
  void TearDown() override {
    master.reset();  // stops the port threads before the pty goes
    ::close(peer);
  }
  uint32_t m(const std::string& a) { return master->read(parse_address(a), 1)[0]; }
  bool scan_until(const std::function<bool()>& pred) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < deadline) {
      master->scan(now += 1000);
      if (pred()) return true;
      std::this_thread::yield();
    }
    return false;
  }
  // Reads what the master sent: blocks on the pty until n bytes came (or 5 s passed).
  std::string peer_read(size_t n) {
    std::string got;
    char buf[64];
    while (got.size() < n && wait_readable(peer, 5000)) {
      const ssize_t k = ::read(peer, buf, sizeof buf);
      if (k > 0) got.append(buf, size_t(k));
    }
    return got;
  }
  std::vector<uint32_t> regs(const std::string& a, uint32_t n) { return master->read(parse_address(a), n); }

  fatek_test::TempDir dir;
  std::unique_ptr<fatek_test::PtyPair> pty;
  std::unique_ptr<Plc> master;
  int peer = -1;
  uint64_t now = 0;
};

}  // namespace

TEST_F(ClinkFree, Md1SendsThenReceivesBetweenStartAndEndCodes) {
  master->write(parse_address("R300"), {0x01, 0x0203, 3, 'A', 'B', 'C'});
  master->write(parse_address("M10"), {1});
  master->scan(now += 1000);
  EXPECT_EQ(peer_read(3), "ABC");
  ASSERT_TRUE(write_all(peer, "zz\x02XY\x03", 6, 1000));  // noise before the start code is dropped
  ASSERT_TRUE(scan_until([&] { return m("Y12") == 1; }));
  EXPECT_EQ(m("R400") >> 8, 0u);
  EXPECT_EQ(m("Y11"), 0u);
  EXPECT_EQ(regs("R408", 5), (std::vector<uint32_t>{4, 0x02, 'X', 'Y', 0x03}));  // count incl. codes
}

TEST_F(ClinkFree, Md1WithoutAnswerTimesOutWithResultA) {
  master->write(parse_address("R300"), {0x01, 0, 1, 'Q'});
  master->write(parse_address("M10"), {1});
  ASSERT_TRUE(scan_until([&] { return m("Y12") == 1; }));
  EXPECT_EQ(m("R400") >> 8, 0xAu);
  EXPECT_EQ(m("Y11"), 1u);
  master->write(parse_address("R302"), {0});  // length 0: result 2
  master->write(parse_address("M10"), {0});
  master->scan(now += 1000);
  master->write(parse_address("M10"), {1});
  ASSERT_TRUE(scan_until([&] { return m("Y12") == 1; }));
  EXPECT_EQ(m("R400") >> 8, 0x2u);
}

TEST_F(ClinkFree, Md2ReceivesByGapAndRepliesWhenTheLengthIsSet) {
  master->write(parse_address("R500"), {0x01, 0});  // receive, then reply; no start/end codes
  master->write(parse_address("M20"), {1});
  master->scan(now += 1000);
  EXPECT_EQ(m("Y20"), 1u);  // ACT: holds the port while waiting
  ASSERT_TRUE(write_all(peer, "HELLO", 5, 1000));
  ASSERT_TRUE(scan_until([&] { return m("Y22") == 1; }));  // the 12 ms gap ended the message
  EXPECT_EQ(regs("R608", 6), (std::vector<uint32_t>{5, 'H', 'E', 'L', 'L', 'O'}));
  master->write(parse_address("R502"), {2, 'O', 'K'});  // the program answers
  ASSERT_TRUE(scan_until([&] { return wait_readable(peer, 0); }));
  EXPECT_EQ(peer_read(2), "OK");
  ASSERT_TRUE(scan_until([&] { return m("R502") == 0; }));
  // EN off releases the port even while a receive is pending.
  master->write(parse_address("M20"), {0});
  EXPECT_TRUE(scan_until([&] { return m("Y20") == 0 && m("M1962") == 1; }));
}

// FUN151 MD0 on a COM port whose slave answers late but in order (the soft PLC's FATEK
// serial server behind a proxy that holds each reply back 250 ms; time-out 200 ms). The two
// packets read one register each: their replies are alike but for the value, and a late
// one must never land in the other packet's master register. After a time-out the master
// waits for the line to be quiet for the time-out before the next packet, so a reply up to
// twice the time-out late is drained; the proxy's 250 ms leave 150 ms for the threads of a
// loaded machine to be late by.
TEST(ClinkLate, ALateReplyIsNeverTakenForTheNextPacket) {
  fatek_test::TempDir dir;
  PtyProxy proxy(dir.path, 1);
  PtyProxy::Faults f;
  f.delay_ms = 250;
  proxy.set_faults(f);
  Plc slave;
  slave.write(parse_address("R0"), {111, 222});
  SerialServerOptions so;
  so.line = parse_serial_settings(proxy.device_link() + ":115200:7E1");
  so.station = 5;
  SerialServer server(slave, so);
  server.start();
  auto ports = std::make_shared<ClinkPorts>();
  ComLine line;
  line.serial = parse_serial_settings(proxy.client_link() + ":115200:7E1");
  ports->set_port(std::make_shared<ComPort>(1, line), 200);
  FunctionTable t = FunctionTable::with_core_functions();
  add_clink_function(t, ports);
  Plc master(std::move(t));
  master.load_program_text(kMaster, "master.il");
  ASSERT_TRUE(master.set_mode(RunMode::Run));
  master.write(parse_address("R100"), {2, 5, 1, 1, 12, 10, 12, 0, 5, 1, 1, 12, 11, 12, 1});
  master.write(parse_address("M0"), {1});
  uint64_t now = 0;
  const auto m = [&](const char* a) { return master.read(parse_address(a), 1)[0]; };
  // Scans until n packets are done (DN pulses); every scan checks the master registers.
  const auto packets = [&](int n) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (n > 0 && std::chrono::steady_clock::now() < end) {
      master.scan(now += 1000);
      const uint32_t r10 = m("R10"), r11 = m("R11");
      EXPECT_TRUE(r10 == 0 || r10 == 111) << r10;
      EXPECT_TRUE(r11 == 0 || r11 == 222) << r11;
      if (r10 == 222 || r11 == 111) return false;
      if (m("Y2")) --n;
      std::this_thread::yield();
    }
    return n == 0;
  };
  ASSERT_TRUE(packets(8));
  EXPECT_EQ(m("R10"), 0u);  // every packet timed out
  EXPECT_EQ(m("R11"), 0u);
  f.delay_ms = 0;
  proxy.set_faults(f);
  ASSERT_TRUE(packets(6));
  EXPECT_EQ(m("R10"), 111u);
  EXPECT_EQ(m("R11"), 222u);
  master.write(parse_address("M0"), {0});
  master.scan(now += 1000);
  server.stop();
}
