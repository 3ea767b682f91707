// Every malformed or out-of-range request class, generated, sent in a loop while the
// scan runs in real time: every one is refused with its exception, the PLC stays in RUN,
// the scans go on and the watchdog (200 ms) never trips. Nothing here asserts on a scan's
// duration, which a loaded machine stretches; `make soak` reports it.
#include <chrono>
#include <functional>

#include <gtest/gtest.h>

#include "plc_cell/core/plc.h"
#include "plc_cell/core/realtime_loop.h"
#include "plc_cell/modbus/slave_handler.h"
#include "plc_cell/modbus/rtu_server.h"
#include "plc_cell/modbus/tcp_server.h"
#include "helpers.h"
#include "wire.h"

namespace plc_cell {
namespace modbus {
namespace {

using test::Bytes;

Bytes pdu(uint8_t fc, uint16_t a, uint16_t n) { return {fc, uint8_t(a >> 8), uint8_t(a), uint8_t(n >> 8), uint8_t(n)}; }

struct Case {
  Bytes pdu;
  int exception;  // -1: a normal reply
};

// The request classes, from the protocol's limits (not from the server's code).
std::vector<Case> generate() {
  std::vector<Case> out;
  for (int fc = 0; fc < 128; ++fc) {
    const bool served = fc == 1 || fc == 2 || fc == 3 || fc == 4 || fc == 5 || fc == 6 || fc == 15 || fc == 16 || fc == 23;
    if (!served) {  // any shape gets 01
      out.push_back({{uint8_t(fc)}, 1});
      out.push_back({pdu(uint8_t(fc), 0, 1), 1});
      out.push_back({pdu(uint8_t(fc), 0xFFFF, 0xFFFF), 1});
      continue;
    }
    out.push_back({{uint8_t(fc)}, 3});                            // truncated to the function code
    out.push_back({{uint8_t(fc), 0, 0, 0}, 3});                   // one byte short of address+quantity
  }
  // Reads: base address mapped for the maximum quantity, the quantity classes.
  struct Read { uint8_t fc; uint16_t base; int max; };
  for (const Read& r : {Read{1, 2000, 2000}, Read{2, 2000, 2000}, Read{3, 0, 125}, Read{4, 0, 125}}) {
    // FC 02 reads M0.. only through the user map; the default 1x map ends at X255.
    const int max_ok = r.fc == 2 ? 2 : -1;
    out.push_back({pdu(r.fc, r.base, 0), 3});
    out.push_back({pdu(r.fc, r.base, uint16_t(r.max)), r.fc == 2 ? 2 : max_ok});
    out.push_back({pdu(r.fc, r.base, uint16_t(r.max + 1)), 3});
    out.push_back({pdu(r.fc, r.base, 65535), 3});
    out.push_back({pdu(r.fc, 65535, 2), 2});
    Bytes longer = pdu(r.fc, r.base, 1);
    longer.push_back(0);
    out.push_back({longer, 3});
  }
  out.push_back({pdu(3, 4168, 1), 2});   // R4168: unmapped
  out.push_back({pdu(1, 256, 1), 2});    // coil 256: unmapped
  out.push_back({pdu(5, 0, 0x1234), 3});
  out.push_back({pdu(5, 256, 0xFF00), 2});
  out.push_back({pdu(6, 4168, 1), 2});
  // FC 15/16: quantity classes and byte counts that disagree.
  for (uint16_t n : {uint16_t(0), uint16_t(1969), uint16_t(65535)}) {
    Bytes b = pdu(15, 0, n);
    b.push_back(uint8_t((n + 7) / 8));
    out.push_back({b, 3});
  }
  for (uint16_t n : {uint16_t(0), uint16_t(124), uint16_t(65535)}) {
    Bytes b = pdu(16, 0, n);
    b.push_back(uint8_t(2 * n));
    out.push_back({b, 3});
  }
  for (int bc : {0, 1, 3, 5, 255}) {
    Bytes b = pdu(16, 0, 2);
    b.push_back(uint8_t(bc));
    b.insert(b.end(), size_t(std::min(bc, 5)), 0);  // 255: a byte count the PDU cannot hold
    out.push_back({b, 3});
  }
  {
    Bytes b = pdu(16, 0, 2);  // byte count right, data short
    b.insert(b.end(), {4, 0, 1});
    out.push_back({b, 3});
  }
  {
    Bytes b = pdu(15, 0, 16);  // byte count 3 for 16 coils
    b.insert(b.end(), {3, 0, 0, 0});
    out.push_back({b, 3});
  }
  // FC 23: read 126, write 122, byte count wrong, read range unmapped.
  auto rw = [](uint16_t ra, uint16_t rn, uint16_t wa, uint16_t wn, int bc, int data) {
    Bytes b = {23, uint8_t(ra >> 8), uint8_t(ra), uint8_t(rn >> 8), uint8_t(rn),
               uint8_t(wa >> 8), uint8_t(wa), uint8_t(wn >> 8), uint8_t(wn), uint8_t(bc)};
    b.insert(b.end(), size_t(data), 0);
    return b;
  };
  out.push_back({rw(0, 126, 10, 1, 2, 2), 3});
  out.push_back({rw(0, 0, 10, 1, 2, 2), 3});
  out.push_back({rw(0, 1, 10, 122, 244, 4), 3});  // 244 data bytes would not fit a PDU
  out.push_back({rw(0, 1, 10, 0, 0, 0), 3});
  out.push_back({rw(0, 1, 10, 1, 3, 3), 3});
  out.push_back({rw(0, 1, 10, 1, 2, 1), 3});
  out.push_back({rw(4168, 1, 10, 1, 2, 2), 2});
  out.push_back({rw(0, 1, 4168, 1, 2, 2), 2});
  return out;
}

constexpr const char* kProgram = "ORG X1\nOUT Y0\nEND\n";

// Sends every refused class `rounds` times through ask (request PDU -> reply PDU) while
// the scan runs at 10 ms, then checks the scan.
void sweep(Plc& plc, const std::function<Bytes(const Bytes&)>& ask, int rounds) {
  const std::vector<Case> cases = generate();
  ASSERT_GT(cases.size(), 400u);
  // A refused request changes nothing.
  const auto snapshot = [&] {
    return plc.locked([](ScanEngine&, Memory& m) {
      std::vector<uint16_t> v;
      for (uint32_t i = 0; i < 4168; ++i) v.push_back(m.reg(Area::R, i));
      for (uint32_t i = 0; i < 256; ++i) v.push_back(m.bit(Area::Y, i));
      return v;
    });
  };
  const auto before = snapshot();
  size_t sent = 0;
  for (int round = 0; round < rounds; ++round) {
    for (const Case& c : cases) {
      if (c.exception < 0) continue;  // only the refused classes here: memory must not move
      const Bytes a = ask(c.pdu);
      ASSERT_EQ(a.size(), 2u) << "request " << sent << " fc " << int(c.pdu[0]);
      EXPECT_EQ(a[0], uint8_t(c.pdu[0] | 0x80)) << "fc " << int(c.pdu[0]);
      EXPECT_EQ(a[1], c.exception) << "fc " << int(c.pdu[0]) << " len " << c.pdu.size();
      ++sent;
    }
  }
  EXPECT_EQ(snapshot(), before);
  // Pass a few more scan periods so the last request's effect on the scan is recorded.
  const uint64_t scans = plc.locked([](ScanEngine& e, Memory&) { return e.stats().scans; });
  for (int i = 0; i < 2000; ++i) {
    if (plc.locked([](ScanEngine& e, Memory&) { return e.stats().scans; }) >= scans + 3) break;
    pollfd none{-1, 0, 0};
    poll(&none, 0, 5);  // bounded wait for the scan thread, not for a result of ours
  }
  const auto st = plc.locked([](ScanEngine& e, Memory&) {
    struct R { RunMode mode; bool wd; std::string fault; ScanStats stats; };
    return R{e.mode(), e.watchdog_tripped(), e.fault(), e.stats()};
  });
  EXPECT_EQ(st.mode, RunMode::Run) << st.fault;
  EXPECT_FALSE(st.wd);
  EXPECT_EQ(st.fault, "");
  // Before the fix one FC03 for 126 registers held the PLC lock 500 ms: a watchdog STOP.
  EXPECT_GT(st.stats.scans, scans);
  EXPECT_GT(sent, size_t(rounds) * 400u);
}

TEST(HostileRequests, GeneratedMalformedRequestsNeverStopTheScan) {
  Plc plc;
  plc.load_program_text(kProgram, "hostile.il");
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  RealTimeLoop loop(plc, std::chrono::milliseconds(10));
  loop.start();
  TcpServerOptions o;
  o.port = 0;
  TcpServer server(plc, o);
  server.start();
  const int fd = test::tcp_connect(server.bound_port());
  ASSERT_GE(fd, 0);
  uint16_t tid = 0;
  sweep(plc, [&](const Bytes& p) {
    if (!test::write_all(fd, test::mbap(++tid, 1, p))) return Bytes{};
    const Bytes a = test::read_tcp_reply(fd);
    return a.size() > 7 ? Bytes(a.begin() + 7, a.end()) : Bytes{};
  }, 5);
  loop.stop();
  server.stop();
  close(fd);
}

TEST(HostileRequests, GeneratedMalformedRequestsOverRtuNeverStopTheScan) {
  test::PtyPair pty("hostile_rtu");
  Plc plc;
  plc.load_program_text(kProgram, "hostile.il");
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  RealTimeLoop loop(plc, std::chrono::milliseconds(10));
  loop.start();
  SerialSettings s;
  s.device = pty.a;
  s.baud = 38400;
  s.data_bits = 8;
  RtuServer server(plc, s, 1);
  server.start();
  const int fd = test::open_raw_tty(pty.b);
  ASSERT_GE(fd, 0);
  sweep(plc, [&](const Bytes& p) {
    if (!test::write_all(fd, test::rtu(1, p))) return Bytes{};
    const Bytes a = test::read_rtu_reply(fd);
    return a.size() > 3 ? Bytes(a.begin() + 1, a.end() - 2) : Bytes{};
  }, 1);
  // A broadcast write (slave 0) is executed and not answered.
  ASSERT_TRUE(test::write_all(fd, test::rtu(0, {6, 0, 20, 0x12, 0x34})));
  EXPECT_TRUE(test::read_rtu_reply(fd, 300).empty());
  EXPECT_EQ(plc.locked([](ScanEngine&, Memory& m) { return m.reg(Area::R, 20); }), 0x1234);
  loop.stop();
  server.stop();
  close(fd);
}

// answer_pdu on the PDU level: the normal classes answer with data of the right size.
TEST(HostileRequests, MaximumQuantitiesAreAnswered) {
  Plc plc;
  uint8_t rsp[kMaxPdu];
  const Bytes r3 = pdu(3, 0, 125), r1 = pdu(1, 2000, 2000);
  PduAnswer a = answer_pdu(plc, r3.data(), int(r3.size()), rsp);
  EXPECT_TRUE(a.accepted);
  EXPECT_EQ(a.length, 2 + 250);
  EXPECT_EQ(rsp[1], 250);
  a = answer_pdu(plc, r1.data(), int(r1.size()), rsp);
  EXPECT_TRUE(a.accepted);
  EXPECT_EQ(a.length, 2 + 250);
}

}  // namespace
}  // namespace modbus
}  // namespace plc_cell
