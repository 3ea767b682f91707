// The TRi map profile (docs/tri.md, "Modbus map"): Table 14.1 through answer_pdu, and
// mbpoll against a Modbus/TCP server serving it: DM[1] at register 1000 (4-1001).
#include <gtest/gtest.h>

#include <fstream>
#include <vector>

#include "helpers.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/modbus/slave_handler.h"
#include "plc_cell/modbus/tcp_server.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {
namespace modbus {
namespace {

struct Reply {
  PduAnswer a;
  std::vector<uint8_t> bytes;
};

Reply call(Plc& plc, std::vector<uint8_t> pdu, const WritableRanges* w = nullptr) {
  Reply r;
  r.bytes.resize(kMaxPdu);
  r.a = answer_pdu(plc, pdu.data(), int(pdu.size()), r.bytes.data(), w, tri_map_profile());
  r.bytes.resize(size_t(r.a.length));
  return r;
}

uint16_t read_word(Plc& plc, uint8_t fc, uint16_t addr) {
  const Reply r = call(plc, {fc, uint8_t(addr >> 8), uint8_t(addr), 0, 1});
  EXPECT_TRUE(r.a.accepted) << "FC" << int(fc) << " " << addr;
  return r.a.accepted ? uint16_t(r.bytes[2] << 8 | r.bytes[3]) : 0xFFFF;
}

bool read_bit(Plc& plc, uint8_t fc, uint16_t addr) {
  const Reply r = call(plc, {fc, uint8_t(addr >> 8), uint8_t(addr), 0, 1});
  EXPECT_TRUE(r.a.accepted) << "FC" << int(fc) << " " << addr;
  return r.a.accepted && (r.bytes[2] & 1);
}

void write_word(Plc& plc, uint16_t addr, uint16_t v) {
  const Reply r = call(plc, {6, uint8_t(addr >> 8), uint8_t(addr), uint8_t(v >> 8), uint8_t(v)});
  EXPECT_TRUE(r.a.accepted) << addr;
}

uint32_t mem(Plc& plc, const std::string& a) { return plc.read(parse_address(a), 1)[0]; }

}  // namespace

// 4-0513..0520: a cell's clock from the first request on, never month 0 or the year 2000
// of cleared registers (before the first scan, after STOP -> RUN).
TEST(TriMap, TheClockBeforeTheFirstScan) {
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/tri_map_clock.yaml") << "cell: {name: clock}\nmodules:\n  rtc: {start: 2026-05-17T08:30:05}\n";
  std::ofstream(dir + "/tri_map_clock.il") << "ORG M1925\nOUT M0\nEND\n";
  SoftCell cell(dir + "/tri_map_clock.yaml", dir + "/tri_map_clock.il");
  for (int pass = 0; pass < 2; ++pass) {
    EXPECT_EQ(read_word(cell.plc(), 3, 512), 8u);      // 4-0513 TIME[1]
    EXPECT_EQ(read_word(cell.plc(), 3, 513), 30u);
    EXPECT_EQ(read_word(cell.plc(), 3, 514), 5u);
    EXPECT_EQ(read_word(cell.plc(), 3, 516), 2026u);   // 4-0517 DATE[1]
    EXPECT_EQ(read_word(cell.plc(), 3, 517), 5u);
    EXPECT_EQ(read_word(cell.plc(), 3, 518), 17u);
    EXPECT_EQ(read_word(cell.plc(), 3, 519), 7u);      // Sunday
    ASSERT_TRUE(cell.plc().set_mode(RunMode::Run));
  }
}

TEST(TriMap, BitsTheSameOnFc01AndFc02) {
  Plc plc;
  plc.write(parse_address("X3"), {1});    // input 4: Modicon 4, wire 3
  plc.write(parse_address("Y1"), {1});    // output 2: wire 257
  plc.write(parse_address("T50"), {1});   // timer 1: wire 512
  plc.write(parse_address("C63"), {1});   // counter 64: wire 831
  plc.write(parse_address("M511"), {1});  // relay 512: wire 1535
  for (uint8_t fc : {1, 2}) {
    EXPECT_TRUE(read_bit(plc, fc, 3));
    EXPECT_FALSE(read_bit(plc, fc, 2));
    EXPECT_TRUE(read_bit(plc, fc, 257));
    EXPECT_TRUE(read_bit(plc, fc, 512));
    EXPECT_TRUE(read_bit(plc, fc, 831));
    EXPECT_TRUE(read_bit(plc, fc, 1535));
  }
  // Writing a "discrete input" is allowed, as on the TRi: FC05 on input 9 (wire 8).
  Reply r = call(plc, {5, 0, 8, 0xFF, 0});
  EXPECT_TRUE(r.a.accepted);
  EXPECT_EQ(mem(plc, "X8"), 1u);
  // Unmapped: between the groups, past the relays.
  for (uint16_t addr : {576, 700, 832, 1536}) {
    r = call(plc, {1, uint8_t(addr >> 8), uint8_t(addr), 0, 1});
    EXPECT_FALSE(r.a.accepted) << addr;
    EXPECT_EQ(r.a.exception, 2) << addr;
  }
  r = call(plc, {2, 0, 250, 0, 10});  // runs from the inputs into the outputs: one map, allowed
  EXPECT_TRUE(r.a.accepted);
}

TEST(TriMap, WordsTheSameOnFc03AndFc04) {
  Plc plc;
  plc.write(parse_address("WX0"), {0x8001});   // INPUT[1] at 4-0001
  plc.write(parse_address("WY0"), {0x1234});   // OUTPUT[1] at 4-0017
  plc.write(parse_address("M496"), {1});       // relay 497: bit 0 of RELAY[32]
  plc.write(parse_address("RT50"), {150});     // timer 1 PV at 4-0129
  plc.write(parse_address("RC63"), {9});       // counter 64 PV at 4-0320
  plc.write(parse_address("R4130"), {14});     // TIME[1] at 4-0513
  plc.write(parse_address("R4133"), {26});     // DATE[1] at 4-0517: 2026
  plc.write(parse_address("R4134"), {0});      // DATE[4]: Sunday = 7
  plc.write(parse_address("DR3760"), {0x00012345});  // A at 4-0715 & 4-0716, high word first
  plc.write(parse_address("DR3810"), {0xABCD0001});  // Z at 4-0765 & 4-0766
  plc.write(parse_address("D0"), {4242});      // DM[1] at 4-1001
  plc.write(parse_address("D3999"), {7});      // DM[4000] at 4-5000
  for (uint8_t fc : {3, 4}) {
    EXPECT_EQ(read_word(plc, fc, 0), 0x8001);
    EXPECT_EQ(read_word(plc, fc, 16), 0x1234);
    EXPECT_EQ(read_word(plc, fc, 95), 1);
    EXPECT_EQ(read_word(plc, fc, 96), 1);  // 4-0097, as the table prints it
    EXPECT_EQ(read_word(plc, fc, 128), 150);
    EXPECT_EQ(read_word(plc, fc, 319), 9);
    EXPECT_EQ(read_word(plc, fc, 512), 14);
    EXPECT_EQ(read_word(plc, fc, 516), 2026);
    EXPECT_EQ(read_word(plc, fc, 519), 7);
    EXPECT_EQ(read_word(plc, fc, 714), 0x0001);
    EXPECT_EQ(read_word(plc, fc, 715), 0x2345);
    EXPECT_EQ(read_word(plc, fc, 764), 0xABCD);
    EXPECT_EQ(read_word(plc, fc, 765), 0x0001);
    EXPECT_EQ(read_word(plc, fc, 1000), 4242);
    EXPECT_EQ(read_word(plc, fc, 4999), 7);
  }
  write_word(plc, 17, 0x00FF);  // OUTPUT[2] = outputs 17..24
  EXPECT_EQ(mem(plc, "WY16") & 0xFFFF, 0x00FFu);
  write_word(plc, 518, 24);     // DATE[3]
  EXPECT_EQ(mem(plc, "R4131"), 24u);
  write_word(plc, 716, 0x0002);  // B high word
  write_word(plc, 717, 0x0003);
  EXPECT_EQ(plc.read(parse_address("DR3762"), 1)[0], 0x00020003u);
  for (uint16_t addr : {36, 52, 97, 127, 192, 255, 320, 511, 515, 520, 713, 766, 999, 5000}) {
    const Reply r = call(plc, {3, uint8_t(addr >> 8), uint8_t(addr), 0, 1});
    EXPECT_FALSE(r.a.accepted) << addr;
    EXPECT_EQ(r.a.exception, 2) << addr;
  }
}

TEST(TriMap, RefusedWritesChangeNothing) {
  Plc plc;
  const WritableRanges w = WritableRanges::parse("D0-D9");
  // FC16 over DM[10], DM[11]: DM[11] = D10 is not writable; DM[10] stays too.
  const Reply r = call(plc, {16, 0x03, 0xF1, 0, 2, 4, 0, 1, 0, 2}, &w);
  EXPECT_FALSE(r.a.accepted);
  EXPECT_EQ(mem(plc, "D9"), 0u);
  EXPECT_TRUE(call(plc, {6, 0x03, 0xF1, 0, 5}, &w).a.accepted);
  EXPECT_EQ(mem(plc, "D9"), 5u);
}

TEST(TriMap, MbpollReadsDm1AtRegister1000) {
  Plc plc;
  plc.write(parse_address("D0"), {1234});
  TcpServerOptions o;
  o.port = 0;
  o.map = &tri_map_profile();
  TcpServer s(plc, o);
  s.start();
  const std::string base = "mbpoll -m tcp -p " + std::to_string(s.bound_port()) + " -a 1 -1 -o 5 ";
  auto out = test::run(base + "-r 1001 -c 1 127.0.0.1");
  ASSERT_EQ(out.status, 0) << out.text;
  EXPECT_NE(out.text.find("[1001]: \t1234"), std::string::npos) << out.text;
  // The same register by its wire address (mbpoll -0: references from 0).
  out = test::run(base + "-0 -r 1000 -c 1 127.0.0.1");
  ASSERT_EQ(out.status, 0) << out.text;
  EXPECT_NE(out.text.find("[1000]: \t1234"), std::string::npos) << out.text;
  // 4-1000 (wire 999) is not in Table 14.1: exception 02, illegal data address.
  out = test::run(base + "-r 1000 -c 1 127.0.0.1");
  EXPECT_NE(out.status, 0) << out.text;
  EXPECT_NE(out.text.find("Illegal data address"), std::string::npos) << out.text;
  out = test::run(base + "-t 3 -r 1 -c 1 127.0.0.1");  // FC04 on INPUT[1]
  ASSERT_EQ(out.status, 0) << out.text;
  EXPECT_NE(out.text.find("[1]: \t0"), std::string::npos) << out.text;
  out = test::run(base + "-r 1002 127.0.0.1 77");  // DM[2] written
  ASSERT_EQ(out.status, 0) << out.text;
  EXPECT_EQ(mem(plc, "D1"), 77u);
  s.stop();
}

TEST(TriMap, ProfileNames) {
  EXPECT_EQ(&map_profile("tri"), &tri_map_profile());
  EXPECT_EQ(&map_profile("fbs"), &fbs_map_profile());
  EXPECT_THROW(map_profile("omron"), std::exception);
}

}  // namespace modbus
}  // namespace plc_cell
