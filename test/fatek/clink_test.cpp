// FUN151 CLINK MD0: a master soft PLC runs a link table against a slave soft PLC over TCP.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <thread>

#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/clink.h"
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
  auto ports = ClinkPorts::from_yaml(f);
  EXPECT_TRUE(ports->has(2));
  EXPECT_FALSE(ports->has(1));
  EXPECT_THROW(ClinkPorts::from_yaml(YAML::Load("ports: {7: 'tcp:127.0.0.1:1'}")), Error);
}
