// FUN151 and FUN150 reach the running PLC: a SoftCell built as `plc_cell run` and plc_node
// build it (with the ProtocolFunctions extension) takes its ports from the cell YAML.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <thread>

#include "plc_cell/core/error.h"
#include "plc_cell/fatek/server.h"
#include "plc_cell/comm/protocol_functions.h"
#include "plc_cell/modbus/slave_servers.h"
#include "plc_cell/sim/soft_cell.h"

using namespace plc_cell;

namespace {

// FUN150/151 with the cell's ports, as the Cell adds them (check: open_ports false).
CellExtensions protocol(bool open_ports = true) {
  CellExtensions x;
  x.push_back(std::make_unique<ProtocolFunctions>(open_ports));
  return x;
}


std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = "/tmp/plc_cell_protocol_functions_" + name;
  std::ofstream(path) << text;
  return path;
}

// Scans (virtual time) until pred holds; the port works on its own thread. No sleeping.
bool scan_until(Plc& plc, const std::function<bool()>& pred) {
  uint64_t now = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (std::chrono::steady_clock::now() < deadline) {
    plc.scan(now += 1000);
    if (pred()) return true;
    std::this_thread::yield();
  }
  return false;
}

uint32_t get(Plc& plc, const char* a) { return plc.read(parse_address(a), 1)[0]; }

// slave's Modbus/TCP server on a free loopback port.
struct ModbusSlave {
  explicit ModbusSlave(Plc& slave) {
    modbus::SlaveOptions so;
    so.tcp = "127.0.0.1:0";
    servers = modbus::make_slave_servers(slave, so);
    servers.at(0)->start();
    const std::string where = servers[0]->describe();  // "Modbus TCP 127.0.0.1:PORT"
    port = std::stoi(where.substr(where.rfind(':') + 1));
  }
  ~ModbusSlave() { servers[0]->stop(); }
  std::vector<std::unique_ptr<Server>> servers;
  int port = 0;
};

// A cell whose FUN150 port 1 talks to 127.0.0.1:port.
std::string mbus_cell(const std::string& name, int port) {
  const std::string prog = write_file(
      name + ".il", "ORG M100\nLD M101\nLD M102\nFUN 150 Pt=1 SR=R100 WR=R200 ACT=M110 ERR=M111 DN=M112\nEND\n");
  return write_file(name + ".yaml", "cell: {program: " + prog + "}\nmodbus:\n  ports:\n    1: {tcp: 127.0.0.1:" +
                                        std::to_string(port) + "}\n");
}

}  // namespace

TEST(ProtocolFunctions, Fun151ReadsAnotherPlcThroughTheCellsFatekPort) {
  Plc slave;
  slave.write(parse_address("R0"), {11, 22, 33});
  fatek::TcpServerOptions o;
  o.port = 0;
  o.station = 5;
  fatek::TcpServer server(slave, o);
  server.start();
  const std::string prog = write_file("clink.il",
                                      "ORG M0\nLD M1\nLD M2\nFUN 151 Pt=1 MD=0 SR=R100 WR=R200 ACT=Y0 ERR=Y1 DN=Y2\nEND\n");
  const std::string cfg = write_file("clink.yaml", "cell: {program: " + prog +
                                                       "}\nfatek:\n  ports:\n    1: tcp:127.0.0.1:" +
                                                       std::to_string(server.port()) + "\n");
  SoftCell cell(cfg, "", protocol());
  Plc& master = cell.plc();
  ASSERT_TRUE(master.set_mode(RunMode::Run));
  // One packet: read slave R0..R2 (type 12) into master R10.. (type 12).
  master.write(parse_address("R100"), {1, 5, 1, 3, 12, 10, 12, 0});
  master.write(parse_address("M0"), {1});
  ASSERT_TRUE(scan_until(master, [&] { return get(master, "Y2") == 1; }));
  EXPECT_EQ(master.read(parse_address("R10"), 3), (std::vector<uint32_t>{11, 22, 33}));
  EXPECT_EQ(get(master, "Y1"), 0u);
  server.stop();
}

TEST(ProtocolFunctions, Fun150ReadsAModbusSlaveThroughTheCellsModbusPort) {
  Plc slave;
  slave.write(parse_address("R7"), {1234, 5678});
  ModbusSlave server(slave);
  const std::string cfg = mbus_cell("mbus", server.port);
  SoftCell cell(cfg, "", protocol());
  Plc& master = cell.plc();
  ASSERT_TRUE(master.set_mode(RunMode::Run));
  // A550H, 07H/1 transaction: station 1, read, 2 words, into R (12) at 20, from 4x (4) reference 8 = R7.
  master.write(parse_address("R100"), {0xA550, 0x0701, 1, 1, 2, 12, 20, 4, 8});
  master.write(parse_address("M100"), {1});
  ASSERT_TRUE(scan_until(master, [&] { return get(master, "M112") == 1 || get(master, "M111") == 1; }));
  EXPECT_EQ(get(master, "M111"), 0u) << "WR+0 = " << get(master, "R200");
  EXPECT_EQ(master.read(parse_address("R20"), 2), (std::vector<uint32_t>{1234, 5678}));
}

TEST(ProtocolFunctions, ABadPortSectionNamesTheFile) {
  const std::string prog = write_file("bad.il", "END\n");
  const std::string cfg = write_file("bad.yaml", "cell: {program: " + prog + "}\nmodbus:\n  ports:\n    9: {tcp: x:1}\n");
  try {
    SoftCell cell(cfg, "", protocol());
    FAIL();
  } catch (const SourceError& e) {
    EXPECT_NE(std::string(e.what()).find(cfg + ":4:5: error: key 'modbus.ports.9'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("ports 1..4"), std::string::npos) << e.what();
  }
}

// `plc_cell check` reads the fatek: and modbus: sections with the same code as the running
// cell (without opening a line), so both refuse a section with the same file:line error.
TEST(ProtocolFunctions, CheckAndRunReadThePortSectionsAlike) {
  const std::string prog = write_file("alike.il", "END\n");
  const struct {
    const char* name;
    const char* section;
    const char* error;
  } bad[] = {
      {"fatek_key", "fatek:\n  timeout: 100\n", ":3:3: error: key 'fatek.timeout': unknown key (expected one of: ports, timeout_ms)"},
      {"fatek_port", "fatek:\n  ports:\n    7: tcp:127.0.0.1:1\n", ":4:5: error: key 'fatek.ports.7': FUN151 port 7 outside 1..4"},
      {"fatek_line", "fatek:\n  ports:\n    1: /dev/ttyS1:9600:7X1\n", ":4:8: error: key 'fatek.ports.1': "},
      {"modbus_key", "modbus:\n  ports:\n    1: {tpc: 127.0.0.1:502}\n",
       ":4:9: error: key 'modbus.ports.1.tpc': unknown key (expected one of: rtu, tcp)"},
  };
  for (const auto& c : bad) {
    const std::string cfg = write_file(std::string(c.name) + ".yaml", "cell: {program: " + prog + "}\n" + c.section);
    std::string errors[2];
    int k = 0;
    for (const bool open_ports : {true, false}) {  // as run, as check
      try {
        SoftCell cell(cfg, "", protocol(open_ports));
        ADD_FAILURE() << c.name << ": accepted";
      } catch (const SourceError& e) {
        errors[k] = e.what();
      }
      ++k;
    }
    EXPECT_EQ(errors[0].rfind(cfg + c.error, 0), 0u) << c.name << ": " << errors[0];
    EXPECT_EQ(errors[0], errors[1]) << c.name;
  }
}

TEST(ProtocolFunctions, Fun150KeepsTheDestinationItSubmittedWith) {
  // The program rewrites its table while a read is on the line: the reply still goes
  // where the table said when the transaction was sent, and nothing else is touched.
  Plc slave;
  slave.write(parse_address("R7"), {4321});
  ModbusSlave server(slave);
  const std::string cfg = mbus_cell("mbus2", server.port);
  SoftCell cell(cfg, "", protocol());
  Plc& master = cell.plc();
  ASSERT_TRUE(master.set_mode(RunMode::Run));
  master.write(parse_address("R100"), {0xA550, 0x0701, 1, 1, 1, 12, 20, 4, 8});
  master.write(parse_address("M100"), {1});
  master.scan(1000);  // submits the read of R7 into R20
  master.write(parse_address("R105"), {99});    // master type: invalid now
  master.write(parse_address("R106"), {8000});  // and a start far away
  uint64_t now = 1000;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (get(master, "M112") == 0 && get(master, "M111") == 0 && std::chrono::steady_clock::now() < deadline) {
    master.scan(now += 1000);
    std::this_thread::yield();
  }
  EXPECT_EQ(get(master, "R20"), 4321u);
  EXPECT_EQ(get(master, "R8000"), 0u);
}

namespace {
// A loopback port nothing listens on (bound once to find it, then closed).
int closed_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  return ntohs(a.sin_port);
}

std::vector<ExtensionStatus> port_statuses(SoftCell& cell) {
  for (const auto& x : cell.extensions())
    if (x->name() == "protocol functions") return x->status(cell.plc());
  ADD_FAILURE() << "no protocol functions extension";
  return {};
}
}  // namespace

// Each COM port reports on /diagnostics (plc_node's "protocol functions" entry): a port
// whose line is up is OK, one whose peer refuses is a WARN that says why.
TEST(ProtocolFunctions, EachPortReportsItsLine) {
  Plc slave;
  ModbusSlave server(slave);
  const int refused = closed_port();
  const std::string prog = write_file("status.il", "END\n");
  const std::string cfg = write_file("status.yaml", "cell: {program: " + prog + "}\nports:\n  1: {tcp: 127.0.0.1:" +
                                                        std::to_string(server.port) + "}\n  3: {tcp: 127.0.0.1:" +
                                                        std::to_string(refused) + "}\n");
  SoftCell cell(cfg, "", protocol());
  const auto s = port_statuses(cell);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].name, "COM1");
  EXPECT_EQ(s[0].level, ExtensionStatus::Level::Ok);
  EXPECT_EQ(s[0].message, "line open");
  EXPECT_EQ(s[0].values.at(0), std::make_pair(std::string("line"), "tcp:127.0.0.1:" + std::to_string(server.port)));
  EXPECT_EQ(s[0].values.at(1), std::make_pair(std::string("held by an instruction"), std::string("no")));
  EXPECT_EQ(s[1].name, "COM3");
  EXPECT_EQ(s[1].level, ExtensionStatus::Level::Warn);
  EXPECT_EQ(s[1].message.rfind("line down: tcp 127.0.0.1:" + std::to_string(refused) + ": cannot connect", 0), 0u)
      << s[1].message;

  SoftCell checked(cfg, "", protocol(false));  // plc_cell check: no port, nothing to report
  EXPECT_TRUE(port_statuses(checked).empty());
}
