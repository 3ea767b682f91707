// The request class -> answer table of docs/modbus.md, read from the page and sent
// verbatim to the TCP server and to the RTU slave (on a socat pty pair).
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include "plc_cell/core/plc.h"
#include "plc_cell/modbus/rtu_server.h"
#include "plc_cell/modbus/tcp_server.h"
#include "helpers.h"
#include "wire.h"

namespace plc_cell {
namespace modbus {
namespace {

struct Row {
  std::string name;
  test::Bytes pdu;
  int exception = -1;  // -1: a normal reply
};

std::vector<Row> table() {
  std::ifstream in(std::string(PLC_CELL_SOURCE_DIR) + "/docs/modbus.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  const auto b = doc.find("<!-- request-classes: begin -->"), e = doc.find("<!-- request-classes: end -->");
  EXPECT_NE(b, std::string::npos);
  EXPECT_NE(e, std::string::npos);
  std::vector<Row> rows;
  if (b == std::string::npos || e == std::string::npos) return rows;
  std::istringstream lines(doc.substr(b, e - b));
  const std::regex row(R"(^\| ([^|]+) \| `([0-9A-F ]+)` \| (reply|exception (0[1-4])) \|$)");
  std::string line;
  while (std::getline(lines, line)) {
    std::smatch m;
    if (line.rfind("| ", 0) != 0 || line.find('`') == std::string::npos) continue;
    EXPECT_TRUE(std::regex_match(line, m, row)) << "unreadable row: " << line;
    if (m.empty()) continue;
    rows.push_back({m[1], test::hex_bytes(m[2]), m[4].matched ? std::stoi(m[4]) : -1});
  }
  return rows;
}

// The answer PDU against the row.
void check(const Row& r, const uint8_t* pdu, size_t len, const std::string& where) {
  SCOPED_TRACE(where + ": " + r.name);
  ASSERT_GE(len, 2u);
  if (r.exception < 0) {
    EXPECT_EQ(pdu[0], r.pdu[0]) << "expected a normal reply, got exception " << int(pdu[1]);
  } else {
    EXPECT_EQ(pdu[0], uint8_t(r.pdu[0] | 0x80));
    EXPECT_EQ(pdu[1], r.exception);
    EXPECT_EQ(len, 2u);
  }
}

TEST(RequestClasses, TableInTheDocsOverTcp) {
  const auto rows = table();
  ASSERT_GE(rows.size(), 40u);
  Plc plc;
  TcpServerOptions o;
  o.port = 0;
  TcpServer server(plc, o);
  server.start();
  const int fd = test::tcp_connect(server.bound_port());
  ASSERT_GE(fd, 0);
  uint16_t tid = 1;
  for (const Row& r : rows) {
    ASSERT_TRUE(test::write_all(fd, test::mbap(tid, 1, r.pdu)));
    const test::Bytes a = test::read_tcp_reply(fd);
    ASSERT_GE(a.size(), 9u) << r.name << ": no answer";
    EXPECT_EQ((a[0] << 8 | a[1]), tid) << r.name;
    check(r, a.data() + 7, a.size() - 7, "TCP");
    ++tid;
  }
  close(fd);
}

TEST(RequestClasses, TableInTheDocsOverRtu) {
  const auto rows = table();
  ASSERT_GE(rows.size(), 40u);
  test::PtyPair pty("classes");
  Plc plc;
  SerialSettings s;
  s.device = pty.a;
  s.baud = 19200;
  s.data_bits = 8;
  RtuServer server(plc, s, 1);
  server.start();
  const int fd = test::open_raw_tty(pty.b);
  ASSERT_GE(fd, 0);
  for (const Row& r : rows) {
    ASSERT_TRUE(test::write_all(fd, test::rtu(1, r.pdu)));
    const test::Bytes a = test::read_rtu_reply(fd);
    ASSERT_GE(a.size(), 5u) << r.name << ": no answer";
    EXPECT_EQ(a[0], 1);
    check(r, a.data() + 1, a.size() - 3, "RTU");
  }
  // Another slave's request, and one with a bad CRC, get no answer; the next one does.
  test::Bytes other = test::rtu(2, test::hex_bytes("03 0000 0001"));
  test::Bytes bad = test::rtu(1, test::hex_bytes("03 0000 0001"));
  bad.back() ^= 0x55;
  ASSERT_TRUE(test::write_all(fd, other));
  EXPECT_TRUE(test::read_rtu_reply(fd, 300).empty());
  ASSERT_TRUE(test::write_all(fd, bad));
  EXPECT_TRUE(test::read_rtu_reply(fd, 300).empty());
  ASSERT_TRUE(test::write_all(fd, test::rtu(1, test::hex_bytes("2B 0E 01 00"))));
  const test::Bytes a = test::read_rtu_reply(fd);
  ASSERT_EQ(a.size(), 5u);
  EXPECT_EQ(a[1], 0xAB);
  EXPECT_EQ(a[2], 1);
  EXPECT_GE(server.status().rejected, 2u);
  close(fd);
}

}  // namespace
}  // namespace modbus
}  // namespace plc_cell
