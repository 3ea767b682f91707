// FUN150 M-BUS: an IL program as Modbus master of a second soft PLC's TCP slave.
#include <chrono>
#include <functional>

#include <gtest/gtest.h>

#include "plc_cell/core/error.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/modbus/fun150.h"
#include "plc_cell/modbus/tcp_server.h"
#include "plc_cell/modbus/rtu_server.h"
#include "plc_cell/io/serial_settings.h"
#include "../reliability/pty_proxy.h"

namespace plc_cell {
namespace modbus {
namespace {

const char* kProgram =
    "ORG M100\n"
    "LD M101\n"
    "LD M102\n"
    "FUN 150 Pt=1 SR=R100 WR=R200 ACT=M110 ERR=M111 DN=M112\n"
    "END\n";

class Fun150 : public ::testing::Test {
 protected:
  void SetUp() override {
    TcpServerOptions o;
    o.port = 0;
    server = std::make_unique<TcpServer>(slave, o);
    server->start();
    FunctionTable t = FunctionTable::with_core_functions();
    std::map<int, MbusPort> ports;
    ports[1].tcp = "127.0.0.1:" + std::to_string(server->bound_port());
    engine = add_fun150(t, ports);
    master = std::make_unique<Plc>(std::move(t));
    master->load_program_text(kProgram, "fun150.il");
    ASSERT_TRUE(master->set_mode(RunMode::Run));
  }
  void TearDown() override {
    master.reset();
    engine.reset();
    server->stop();
  }
  void table(const std::vector<uint16_t>& words) {
    master->locked([&](ScanEngine&, Memory& m) {
      for (size_t i = 0; i < words.size(); ++i) m.set_reg(Area::R, 100 + uint32_t(i), words[i]);
      return 0;
    });
  }
  void set_m(uint32_t i, bool v) {
    master->locked([&](ScanEngine&, Memory& m) { m.set_bit(Area::M, i, v); return 0; });
  }
  bool m(uint32_t i) { return master->locked([&](ScanEngine&, Memory& mem) { return mem.bit(Area::M, i); }); }
  uint16_t r(Plc& p, Area a, uint32_t i) { return p.locked([&](ScanEngine&, Memory& mem) { return mem.reg(a, i); }); }
  // Scans (the PLC's own work, not a sleep) until DN, bounded by 10 s.
  bool run_until_done() {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < end) {
      now_us += 1000;
      master->scan(now_us);
      if (m(112)) return true;
    }
    return false;
  }

  Plc slave;
  std::unique_ptr<TcpServer> server;
  std::shared_ptr<MbusEngine> engine;
  std::unique_ptr<Plc> master;
  uint64_t now_us = 0;
};

TEST_F(Fun150, ReadsAndWritesASlaveFromTheTable) {
  slave.locked([](ScanEngine&, Memory& mem) {
    for (uint32_t i = 0; i < 4; ++i) mem.set_reg(Area::R, 5 + i, uint16_t(11 * (i + 1)));
    return 0;
  });
  master->locked([](ScanEngine&, Memory& mem) {
    mem.set_bit(Area::M, 20, true);
    mem.set_bit(Area::M, 22, true);
    mem.set_reg(Area::D, 0, 777);
    return 0;
  });
  table({0xA550, 0x0703,
         1, 1, 4, 12, 10, 4, 6,     // read 4 holding registers 400006.. into R10..R13
         1, 2, 3, 2, 20, 0, 1,      // write M20..M22 to coils 000001.. (Y0..Y2)
         1, 3, 1, 13, 0, 4, 101});  // write D0 to holding register 400101 (R100)
  set_m(100, true);
  ASSERT_TRUE(run_until_done());
  EXPECT_FALSE(m(111));  // ERR
  EXPECT_FALSE(m(110));  // ACT
  for (uint32_t i = 0; i < 4; ++i) EXPECT_EQ(r(*master, Area::R, 10 + i), 11 * (i + 1));
  EXPECT_TRUE(slave.locked([](ScanEngine&, Memory& mem) {
    return mem.bit(Area::Y, 0) && !mem.bit(Area::Y, 1) && mem.bit(Area::Y, 2);
  }));
  EXPECT_EQ(r(slave, Area::R, 100), 777);
  EXPECT_EQ(r(*master, Area::R, 200), 0x0002);  // result 0, last transaction no. 2
  EXPECT_EQ(r(*master, Area::R, 201), 0x0106);  // station 1, FC 06
  EXPECT_EQ(r(*master, Area::R, 204) & 0x4000, 0x4000);  // WR+4 b14 DN
}

TEST_F(Fun150, ResultCodes) {
  // An exception reply (unmapped address on the slave): B, ERR.
  table({0xA550, 0x0701, 1, 1, 1, 12, 10, 4, 4169});
  set_m(100, true);
  ASSERT_TRUE(run_until_done());
  EXPECT_TRUE(m(111));
  EXPECT_EQ(r(*master, Area::R, 200) >> 8, mbus_result::kCommError);
  // A table without A550H: 8.
  set_m(100, false);
  now_us += 1000;
  master->scan(now_us);
  table({0x1234, 0x0701});
  set_m(100, true);
  ASSERT_TRUE(run_until_done());
  EXPECT_EQ(r(*master, Area::R, 200) >> 8, mbus_result::kTable);
  // Bit master type with a register slave type: 6; command 4: 3.
  set_m(100, false);
  now_us += 1000;
  master->scan(now_us);
  table({0xA550, 0x0702, 1, 1, 1, 2, 0, 4, 1, 1, 4, 1, 12, 0, 4, 1});
  set_m(100, true);
  ASSERT_TRUE(run_until_done());
  EXPECT_EQ(r(*master, Area::R, 200), 0x0301);  // the last one: command error, transaction 1
  EXPECT_TRUE(m(111));
}

// FUN150 on an RTU port whose slave answers late but in order (the soft PLC's RTU slave
// behind a proxy that holds each reply back 300 ms; R4147 = 20: 200 ms). The two
// transactions read one register each: their replies are alike but for the value, and a
// late one must never land in the other's master register. After a timeout the port is
// drained until quiet for the timeout, so the replies come between the timeout and twice
// it, 100 ms from either: a loaded machine's late threads do not make a reply in time, nor
// one later than the drain.
TEST(Fun150Late, ALateReplyIsNeverTakenForTheNextTransaction) {
  {
    LateDeviceLine proxy(300);
    Plc slave;
    slave.locked([](ScanEngine&, Memory& m) {
      m.set_reg(Area::R, 0, 111);
      m.set_reg(Area::R, 1, 222);
      return 0;
    });
    RtuServer rtu(slave, parse_serial_settings(proxy.device_link() + ":115200:8E1"), 1);
    rtu.start();
    FunctionTable t = FunctionTable::with_core_functions();
    std::map<int, MbusPort> ports;
    ports[1].rtu = proxy.client_link() + ":115200:8E1";
    auto engine = add_fun150(t, ports);
    Plc master(std::move(t));
    master.load_program_text(kProgram, "fun150.il");
    ASSERT_TRUE(master.set_mode(RunMode::Run));
    master.locked([](ScanEngine&, Memory& m) {
      m.set_reg(Area::R, 4147, 20);  // 200 ms
      const uint16_t table[] = {0xA550, 0x0702, 1, 1, 1, 12, 10, 4, 1, 1, 1, 1, 12, 11, 4, 2};
      for (uint32_t i = 0; i < 16; ++i) m.set_reg(Area::R, 100 + i, table[i]);
      m.set_bit(Area::M, 100, true);
      return 0;
    });
    uint64_t now = 0;
    const auto reg = [&](uint32_t i) { return master.locked([&](ScanEngine&, Memory& m) { return m.reg(Area::R, i); }); };
    const auto done = [&] { return master.locked([&](ScanEngine&, Memory& m) { return m.bit(Area::M, 112); }); };
    // Scans (the PLC's own work) until pred, bounded by 20 s; every scan checks the registers.
    const auto scan_until = [&](const std::function<bool()>& pred) {
      const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (std::chrono::steady_clock::now() < end) {
        master.scan(now += 1000);
        const uint16_t r10 = reg(10), r11 = reg(11);
        EXPECT_TRUE(r10 == 0 || r10 == 111) << r10;
        EXPECT_TRUE(r11 == 0 || r11 == 222) << r11;
        if (r10 == 222 || r11 == 111) return false;
        if (pred()) return true;
      }
      return false;
    };
    const auto en = [&](bool on) {
      master.locked([&](ScanEngine&, Memory& m) {
        m.set_bit(Area::M, 100, on);
        return 0;
      });
      master.scan(now += 1000);
    };
    for (int round = 0; round < 4; ++round) {  // the table again and again
      ASSERT_TRUE(scan_until(done));
      en(false);
      en(true);
    }
    EXPECT_EQ(reg(10), 0u);  // every transaction timed out
    EXPECT_EQ(reg(11), 0u);
    proxy.set_delay_ms(0);
    for (int round = 0; round < 3 && !(reg(10) == 111 && reg(11) == 222); ++round) {
      ASSERT_TRUE(scan_until(done));
      en(false);
      en(true);
    }
    EXPECT_EQ(reg(10), 111u);
    EXPECT_EQ(reg(11), 222u);
    master.locked([](ScanEngine&, Memory& m) {
      m.set_bit(Area::M, 100, false);
      return 0;
    });
    master.scan(now += 1000);
    rtu.stop();
  }
}

TEST(Fun150Ports, UnconfiguredPortAndYaml) {
  FunctionTable t = FunctionTable::with_core_functions();
  auto engine = add_fun150(t, {});
  Plc plc(std::move(t));
  plc.load_program_text("ORG M100\nLD M101\nLD M102\nFUN 150 Pt=2 SR=R100 WR=R200 DN=M112\nEND\n", "p.il");
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  plc.locked([](ScanEngine&, Memory& m) { m.set_bit(Area::M, 100, true); return 0; });
  plc.scan(1000);
  EXPECT_EQ(plc.locked([](ScanEngine&, Memory& m) { return m.reg(Area::R, 200); }) >> 8, mbus_result::kPort);
  const auto ports = parse_mbus_ports(YAML::Load("ports: {1: {rtu: /dev/ttyS1:19200}, 3: {tcp: '10.0.0.2:502'}}"), "cell.yaml");
  ASSERT_EQ(ports.size(), 2u);
  EXPECT_EQ(ports.at(1).rtu, "/dev/ttyS1:19200");
  EXPECT_THROW(parse_mbus_ports(YAML::Load("ports: {5: {tcp: 'a:1'}}"), "cell.yaml"), Error);
}

// modbus: is read by the cell's YAML reader: every key and line is checked, and an error
// names file:line:column and the key (docs/modbus.md).
TEST(Fun150Config, ErrorsNameFileLineAndKey) {
  const auto error = [](const std::string& yaml) {
    try {
      parse_mbus_ports(YAML::Load(yaml)["modbus"], "cell.yaml");
    } catch (const SourceError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("modbus:\n  port: {}\n"), "cell.yaml:2:3: error: key 'modbus.port': unknown key (expected one of: ports)");
  EXPECT_EQ(error("modbus:\n  ports:\n    1: {tpc: 127.0.0.1:502}\n"),
            "cell.yaml:3:9: error: key 'modbus.ports.1.tpc': unknown key (expected one of: rtu, tcp)");
  EXPECT_EQ(error("modbus:\n  ports:\n    9: {tcp: 127.0.0.1:502}\n"),
            "cell.yaml:3:5: error: key 'modbus.ports.9': port 9 (FUN150 uses ports 1..4)");
  EXPECT_EQ(error("modbus:\n  ports:\n    1: {tcp: 127.0.0.1:502, rtu: /dev/ttyS1}\n"),
            "cell.yaml:3:8: error: key 'modbus.ports.1': give one of tcp or rtu");
  EXPECT_EQ(error("modbus:\n  ports:\n    1: {rtu: /dev/ttyS1:9600:9Z1}\n").rfind("cell.yaml:3:14: error: key 'modbus.ports.1.rtu': ", 0), 0u);
  EXPECT_EQ(error("modbus:\n  ports:\n    1: {tcp: 127.0.0.1:99999}\n").rfind("cell.yaml:3:14: error: key 'modbus.ports.1.tcp': ", 0), 0u);
  EXPECT_EQ(parse_mbus_ports(YAML::Load("cell: {}")["modbus"], "cell.yaml").size(), 0u);
}

}  // namespace
}  // namespace modbus
}  // namespace plc_cell
