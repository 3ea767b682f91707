// The slave on a soft PLC with the manual's examples, byte for byte, and the memory map
// behind each command (docs/tri.md, "Memory map").
#include <gtest/gtest.h>

#include <fstream>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/sim/soft_cell.h"
#include "plc_cell/tri/fcs.h"
#include "plc_cell/tri/memory_map.h"
#include "plc_cell/tri/slave.h"

using namespace plc_cell;
using namespace plc_cell::tri;

namespace {

class TriSlave : public ::testing::Test {
 protected:
  uint32_t mem(const std::string& a) { return plc.read(parse_address(a), 1)[0]; }
  void set(const std::string& a, uint32_t v) { plc.write(parse_address(a), {v}); }
  // Point-to-point: the body with '*' CR, answered without the CR.
  std::string p2p(const std::string& body) {
    std::string r = slave.answer(body + "*\r");
    if (!r.empty() && r.back() == '\r') r.pop_back();
    return r;
  }
  std::string mp(const std::string& body, int id = 1) {
    Frame f;
    f.multipoint = true;
    f.id = id;
    f.body = body;
    return slave.answer(encode_frame(f));
  }
  Plc plc;
  Slave slave{plc, 1};
};

std::string mp_reply(const std::string& body, int id = 1) {
  Frame f;
  f.multipoint = true;
  f.id = id;
  f.body = body;
  return encode_frame(f);
}

}  // namespace

TEST_F(TriSlave, ManualExamples) {
  set("D3599", 12345);  // DM[3600]
  EXPECT_EQ(p2p("RVD0E10"), "RVD3039*");
  EXPECT_EQ(p2p("WVD03E804D2"), "WVD*");
  EXPECT_EQ(mem("D999"), 1234u);  // DM[1000]
  plc.write(parse_address("DR3780"), {123456});  // K = A + 10
  EXPECT_EQ(p2p("RVIK"), "RVI0001E240*");
  EXPECT_EQ(p2p("wb0100FF"), "wb*");
  EXPECT_EQ(mem("Y0"), 1u);  // output 1
  EXPECT_EQ(p2p("wb010000"), "wb*");
  EXPECT_EQ(mem("Y0"), 0u);
  plc.locked([](ScanEngine&, Memory& m) {
    for (uint32_t x = 3; x <= 9; ++x) m.set_bit(Area::X, x, true);
    return 0;
  });
  EXPECT_EQ(p2p("RI00"), "RIF8*");
  EXPECT_EQ(p2p("RI01"), "RI03*");
  plc.write(parse_address("DR4100"), {123456});  // HSCPV[2]
  EXPECT_EQ(p2p("RVH2"), "RVH0001E240*");
  EXPECT_EQ(p2p("wvH200000000"), "wvH*");
  EXPECT_EQ(mem("DR4100"), 0u);
  EXPECT_EQ(p2p("WVS0801000E"), "WVS*");
  EXPECT_EQ(mem("R4130"), 14u);  // hour
  set("R4132", 5);
  EXPECT_EQ(p2p("RVS0902"), "RVS0005*");  // May
  // PWM (RVS/WVS type 0D, §16.15/16.29): the duty of the last SETPWM in 0.01 %, kept in
  // R3812.. (SETPWM 2, 9500, 50 is 95 %).
  EXPECT_EQ(p2p("WVS0D02251C"), "WVS*");
  EXPECT_EQ(mem("R3813"), 9500u);
  set("R3812", 5000);
  EXPECT_EQ(p2p("RVS0D01"), "RVS1388*");
  EXPECT_EQ(p2p("IR"), "IR01*");
  EXPECT_EQ(p2p("IW0A"), "IW*");
  EXPECT_EQ(slave.id(), 10);
  EXPECT_EQ(p2p("IR"), "IR0A*");
  EXPECT_EQ(p2p("WVIK00000DD5"), "WVI*");
  EXPECT_EQ(mem("DR3780"), 3541u);  // 0x0DD5, not the 56789 the text says
  EXPECT_EQ(p2p("WV$P Super PLC"), "WV$*");
  EXPECT_EQ(p2p("RV$P"), "RV$ Super PLC*");
  EXPECT_EQ(p2p("WX$000CHello TRi"), "WX$*");
  EXPECT_EQ(p2p("RX$000C"), "RX$Hello TRi*");
  for (uint32_t i = 0; i < 10; ++i) set("F" + std::to_string(99 + i), i + 1);  // EEPROM 100..109
  EXPECT_EQ(p2p("RXI00640A"), "RXI000100020003000400050006000700080009000A*");
  for (uint32_t c = 2; c <= 5; ++c) set("R" + std::to_string(3839 + c), c * 100);
  EXPECT_EQ(p2p("RA0204"), "RA00C8012C019001F4*");
}

TEST_F(TriSlave, MultiPointFramesCarryIdAndFcs) {
  EXPECT_EQ(mp("RI02"), mp_reply("RI00"));
  EXPECT_EQ(slave.answer("@01RI0258*\r"), mp_reply("RI00"));
  EXPECT_EQ(slave.answer("@01RI0200*\r"), mp_reply("RI00"));  // wildcard FCS
  EXPECT_EQ(slave.answer("@01RI0200*\r", /*wildcard=*/false), mp_reply("FE"));
  EXPECT_EQ(slave.answer("@01RI0259*\r"), mp_reply("FE"));  // framing error
  EXPECT_EQ(slave.answer("@02RI0200*\r"), "");             // another PLC's: silent
  EXPECT_EQ(slave.answer("@02RI0259*\r"), "");
  EXPECT_EQ(mp("XX"), mp_reply("ER01"));
  EXPECT_EQ(slave.answer("@04RVIA48*\r"), "");
  Slave four(plc, 4);
  plc.write(parse_address("DR3760"), {7});
  EXPECT_EQ(four.answer("@04RVIA48*\r"), mp_reply("RVI00000007", 4));
  // IW answers under the ID it was addressed to, then the new one applies.
  EXPECT_EQ(mp("IW22"), mp_reply("IW"));
  EXPECT_EQ(mp("IR", 0x22), mp_reply("IR22", 0x22));
}

TEST_F(TriSlave, CtrlEHandshakeIsEchoed) {
  EXPECT_EQ(slave.answer("\x05"), "\x05");
  EXPECT_EQ(slave.answer("\x05IR*\r"), "\x05IR01*\r");
}

TEST_F(TriSlave, ChannelsAndBitsFollowTheMap) {
  EXPECT_EQ(p2p("WO01A5"), "WO*");  // outputs 9..16
  EXPECT_EQ(mem("WY8") & 0xFF, 0xA5u);
  EXPECT_EQ(p2p("RO01"), "ROA5*");
  EXPECT_EQ(p2p("WR3F80"), "WR*");  // relay 512
  EXPECT_EQ(mem("M511"), 1u);
  EXPECT_EQ(p2p("RR3F"), "RR80*");
  EXPECT_EQ(p2p("wb05FFFF"), "wb*");  // relay 512 again, by bit address
  EXPECT_EQ(p2p("wb04FF00"), "wb*");  // relay 256
  EXPECT_EQ(mem("M255"), 0u);
  EXPECT_EQ(p2p("wb0000FF"), "wb*");  // input 1 plays the sensor
  EXPECT_EQ(mem("X0"), 1u);
  EXPECT_EQ(p2p("WT0001"), "WT*");  // timer 1 = T50
  EXPECT_EQ(mem("T50"), 1u);
  EXPECT_EQ(p2p("RT00"), "RT01*");
  EXPECT_EQ(p2p("wb023FFF"), "wb*");  // timer 64 = T113
  EXPECT_EQ(mem("T113"), 1u);
  EXPECT_EQ(p2p("WC0780"), "WC*");  // counter 64 = C63
  EXPECT_EQ(mem("C63"), 1u);
  EXPECT_EQ(p2p("RC07"), "RC80*");
  EXPECT_EQ(p2p("wb0300FF"), "wb*");  // counter 1 = C0
  EXPECT_EQ(mem("C0"), 1u);
  // RVS words: 16 discretes, bit 0 the lowest-numbered.
  EXPECT_EQ(p2p("WVS02011234"), "WVS*");
  EXPECT_EQ(mem("WY0"), 0x1234u);
  EXPECT_EQ(p2p("RVS0201"), "RVS1234*");
  EXPECT_EQ(p2p("RVS0320"), "RVS8000*");  // relay[32]: relays 497..512
}

TEST_F(TriSlave, TimersAndCountersFollowTheMap) {
  EXPECT_EQ(p2p("WM000150"), "WM*");  // timer 1 PV = RT50
  EXPECT_EQ(mem("RT50"), 150u);
  EXPECT_EQ(p2p("RM00"), "RM0150*");
  EXPECT_EQ(p2p("Wm3F0300"), "Wm*");  // timer 64 SV = R3663
  EXPECT_EQ(mem("R3663"), 300u);
  EXPECT_EQ(p2p("Rm3F"), "Rm0300*");
  EXPECT_EQ(p2p("WU050007"), "WU*");  // counter 6 PV = RC5
  EXPECT_EQ(mem("RC5"), 7u);
  EXPECT_EQ(p2p("RU05"), "RU0007*");
  EXPECT_EQ(p2p("Wu000010"), "Wu*");  // counter 1 SV = R3664
  EXPECT_EQ(mem("R3664"), 10u);
  EXPECT_EQ(p2p("Ru00"), "Ru0010*");
  set("RT51", 12000);  // beyond 4 digits: reported as 9999
  EXPECT_EQ(p2p("RM01"), "RM9999*");
  EXPECT_EQ(p2p("RVS0602"), "RVS2EE0*");  // RVS reads the whole word
  EXPECT_EQ(p2p("RVS0706"), "RVS0007*");
}

TEST_F(TriSlave, ClockAndDate) {
  set("R4133", 26);
  set("R4131", 25);
  set("R4134", 0);  // Sunday on the FBs
  EXPECT_EQ(p2p("RVS0901"), "RVS07EA*");  // 2026
  EXPECT_EQ(p2p("RVS0903"), "RVS0019*");
  EXPECT_EQ(p2p("RVS0904"), "RVS0007*");  // 7 = Sunday on the TRi
  EXPECT_EQ(p2p("WVS090107E9"), "WVS*");
  EXPECT_EQ(mem("R4133"), 25u);
  EXPECT_EQ(p2p("WVS09040001"), "WVS*");  // Monday
  EXPECT_EQ(mem("R4134"), 1u);
  set("R4129", 59);
  set("R4128", 7);
  EXPECT_EQ(p2p("RVS0802"), "RVS003B*");
  EXPECT_EQ(p2p("RVS0803"), "RVS0007*");
}

// A real TRi never reports month 0: a cell's clock is served from the first request on,
// before the first scan and right after STOP -> RUN.
TEST(TriSlaveCell, TheClockBeforeTheFirstScan) {
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/tri_clock.yaml") << "cell: {name: clock}\nmodules:\n  rtc: {start: 2026-05-17T08:30:05}\n";
  std::ofstream(dir + "/tri_clock.il") << "ORG M1925\nOUT M0\nEND\n";
  SoftCell cell(dir + "/tri_clock.yaml", dir + "/tri_clock.il");
  Slave slave(cell.plc(), 1);
  const auto ask = [&](const std::string& body) { return slave.answer(body + "*\r"); };
  EXPECT_EQ(ask("RVS0901"), "RVS07EA*\r");  // 2026
  EXPECT_EQ(ask("RVS0902"), "RVS0005*\r");  // May
  EXPECT_EQ(ask("RVS0903"), "RVS0011*\r");  // the 17th
  EXPECT_EQ(ask("RVS0904"), "RVS0007*\r");  // a Sunday
  EXPECT_EQ(ask("RVS0801"), "RVS0008*\r");
  EXPECT_EQ(ask("RVS0802"), "RVS001E*\r");
  EXPECT_EQ(ask("RVS0803"), "RVS0005*\r");
  ASSERT_TRUE(cell.plc().set_mode(RunMode::Run));
  EXPECT_EQ(ask("RVS0902"), "RVS0005*\r");
  EXPECT_EQ(ask("RVS0901"), "RVS07EA*\r");
}

TEST_F(TriSlave, RangesAreCheckedAndRefusedRequestsChangeNothing) {
  EXPECT_EQ(p2p("RVD0000"), "ER03*");  // DM[0]
  EXPECT_EQ(p2p("RVD0FA1"), "ER03*");  // DM[4001]
  EXPECT_EQ(p2p("RVD0FA0"), "RVD0000*");
  EXPECT_EQ(p2p("RI20"), "ER03*");
  EXPECT_EQ(p2p("RR40"), "ER03*");
  EXPECT_EQ(p2p("RT08"), "ER03*");
  EXPECT_EQ(p2p("RM40"), "ER03*");
  EXPECT_EQ(p2p("RVH3"), "ER03*");
  EXPECT_EQ(p2p("RVS0A01"), "ER03*");
  EXPECT_EQ(p2p("RVS0D05"), "ER03*");  // PWM 1-4
  EXPECT_EQ(p2p("RVS0111"), "ER03*");  // input[17]
  EXPECT_EQ(p2p("RA0802"), "ER03*");
  EXPECT_EQ(p2p("WA0501FFFF"), "ER03*");
  EXPECT_EQ(p2p("wb0240FF"), "ER03*");  // timer 65
  EXPECT_EQ(p2p("wb0600FF"), "ER03*");
  EXPECT_EQ(p2p("RXI0FA002"), "ER03*");  // 4000 and 4001
  EXPECT_EQ(p2p("WXI0001110000000000000000000000000000000000000000000000000000000000000000"), "ER02*");
  EXPECT_EQ(p2p("RXI000100"), "ER02*");
  EXPECT_EQ(p2p("WV$A" + std::string(71, 'x')), "ER03*");
  EXPECT_EQ(p2p("WX$0001" + std::string(41, 'x')), "ER03*");
  EXPECT_EQ(p2p("RX$0000"), "ER03*");
  EXPECT_EQ(p2p("ZZ"), "ER01*");
  EXPECT_EQ(p2p("RVD0E1"), "ER02*");
  EXPECT_EQ(slave.answer("RVD0E10\r"), "");  // no '*': not a frame, silent
  // A read of more than 32 words gives the first 32.
  const std::string r = p2p("RXI000140");
  EXPECT_EQ(r.size(), 3u + 32 * 4 + 1);

  // Writable ranges: a write outside them is refused and changes nothing.
  slave.set_writable(WritableRanges::parse("D0-D99"));
  EXPECT_EQ(p2p("WVD00010001"), "WVD*");
  EXPECT_EQ(mem("D0"), 1u);
  EXPECT_EQ(p2p("WVD00650001"), "ER04*");  // DM[101] = D100
  EXPECT_EQ(mem("D100"), 0u);
  EXPECT_EQ(p2p("WO00FF"), "ER04*");
  EXPECT_EQ(mem("WY0"), 0u);
  EXPECT_EQ(p2p("C2"), "ER04*");
  EXPECT_EQ(p2p("IW05"), "ER04*");
  EXPECT_EQ(p2p("RVD0001"), "RVD0001*");  // reads are always allowed
}

TEST_F(TriSlave, HaltAndResume) {
  plc.load_program_text("ORG X0\nOUT Y0\nEND\n", "t.il");
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  EXPECT_EQ(p2p("C3"), "C3*");  // not halted: no effect
  EXPECT_EQ(plc.mode(), RunMode::Run);
  EXPECT_EQ(p2p("C2"), "C2*");
  EXPECT_EQ(plc.mode(), RunMode::Stop);
  EXPECT_EQ(p2p("RVD0001"), "RVD0000*");  // host link goes on while halted
  EXPECT_EQ(p2p("C3"), "C3*");
  EXPECT_EQ(plc.mode(), RunMode::Run);
  plc.set_mode(RunMode::Stop);  // stopped by someone else: C3 does not start it
  EXPECT_EQ(p2p("C3"), "C3*");
  EXPECT_EQ(plc.mode(), RunMode::Stop);
}

TEST(TriMemoryMap, TheDocumentedTable) {
  Address a;
  ASSERT_TRUE(bit_address(BitKind::Input, 1, &a));
  EXPECT_EQ(format_address(a), "X0");
  ASSERT_TRUE(bit_address(BitKind::Output, 256, &a));
  EXPECT_EQ(format_address(a), "Y255");
  ASSERT_TRUE(bit_address(BitKind::Relay, 512, &a));
  EXPECT_EQ(format_address(a), "M511");
  ASSERT_TRUE(bit_address(BitKind::Timer, 1, &a));
  EXPECT_EQ(format_address(a), "T50");
  ASSERT_TRUE(bit_address(BitKind::Timer, 64, &a));
  EXPECT_EQ(format_address(a), "T113");
  ASSERT_TRUE(bit_address(BitKind::Counter, 64, &a));
  EXPECT_EQ(format_address(a), "C63");
  EXPECT_FALSE(bit_address(BitKind::Input, 0, &a));
  EXPECT_FALSE(bit_address(BitKind::Relay, 513, &a));
  EXPECT_FALSE(bit_address(BitKind::Timer, 65, &a));
  EXPECT_EQ(format_address(timer_pv(1)), "RT50");
  EXPECT_EQ(format_address(timer_pv(64)), "RT113");
  EXPECT_EQ(format_address(timer_sv(1)), "R3600");
  EXPECT_EQ(format_address(counter_pv(1)), "RC0");
  EXPECT_EQ(format_address(counter_sv(64)), "R3727");
  ASSERT_TRUE(integer_var(0, &a));
  EXPECT_EQ(format_address(a), "DR3760");
  ASSERT_TRUE(integer_var(25, &a));
  EXPECT_EQ(format_address(a), "DR3810");
  EXPECT_FALSE(integer_var(26, &a));
  ASSERT_TRUE(dm(1, &a));
  EXPECT_EQ(format_address(a), "D0");
  ASSERT_TRUE(dm(4000, &a));
  EXPECT_EQ(format_address(a), "D3999");
  EXPECT_FALSE(dm(0, &a));
  EXPECT_FALSE(dm(4001, &a));
  ASSERT_TRUE(hsc_pv(1, &a));
  EXPECT_EQ(format_address(a), "DR4096");
  ASSERT_TRUE(hsc_pv(2, &a));
  EXPECT_EQ(format_address(a), "DR4100");
  ASSERT_TRUE(adc(8, &a));
  EXPECT_EQ(format_address(a), "R3847");
  ASSERT_TRUE(dac(1, &a));
  EXPECT_EQ(format_address(a), "R3904");
  ASSERT_TRUE(pwm(1, &a));
  EXPECT_EQ(format_address(a), "R3812");
  ASSERT_TRUE(pwm(4, &a));
  EXPECT_EQ(format_address(a), "R3815");
  EXPECT_FALSE(pwm(0, &a));
  EXPECT_FALSE(pwm(5, &a));
  ASSERT_TRUE(eeprom_int(4000, &a));
  EXPECT_EQ(format_address(a), "F3999");
  ASSERT_TRUE(eeprom_string(150, &a));
  EXPECT_EQ(format_address(a), "F6980");
  ASSERT_TRUE(string_var(25, &a));
  EXPECT_EQ(format_address(a), "F7875");
  ASSERT_TRUE(time_register(1, &a));
  EXPECT_EQ(format_address(a), "R4130");
  ASSERT_TRUE(date_register(4, &a));
  EXPECT_EQ(format_address(a), "R4134");
  // The general registers used stay clear of the FBs special ones (R3840.. are I/O).
  EXPECT_LT(kIntegersR + 52, 3840u);
  EXPECT_LE(kTimerSvR + kTimers, kCounterSvR);
  EXPECT_LE(kCounterSvR + kCounters, kIntegersR);
  EXPECT_LE(kIntegersR + 52, kPwmR);
  EXPECT_LE(kPwmR + kPwmChannels, 3840u);
}

// What survives STOP -> RUN is the cell's plc.retentive: with the FBs default, DM[], A-Z,
// the SVs and the EEPROM stay (the TRi with FRAM and DIPSW1 on); relays and outputs go.
TEST_F(TriSlave, VolatileFollowsTheRetentiveRanges) {
  EXPECT_EQ(p2p("WVD00010007"), "WVD*");
  EXPECT_EQ(p2p("WVIZ00000009"), "WVI*");
  EXPECT_EQ(p2p("Wm000100"), "Wm*");
  EXPECT_EQ(p2p("WXI0001010005"), "WXI*");
  EXPECT_EQ(p2p("WR0001"), "WR*");
  EXPECT_EQ(p2p("WO0001"), "WO*");
  plc.locked([](ScanEngine&, Memory& m) {
    m.clear_non_retentive(CellConfig::default_retentive());
    return 0;
  });
  EXPECT_EQ(p2p("RVD0001"), "RVD0007*");
  EXPECT_EQ(p2p("RVIZ"), "RVI00000009*");
  EXPECT_EQ(p2p("Rm00"), "Rm0100*");
  EXPECT_EQ(p2p("RXI000101"), "RXI0005*");
  EXPECT_EQ(p2p("RR00"), "RR00*");
  EXPECT_EQ(p2p("RO00"), "RO00*");
}
