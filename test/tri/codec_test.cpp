// The host-link codec against the manual's own examples (chapters 15 and 16): FCS,
// framing both ways, every command's request and response layout, the streaming decoder.
#include <gtest/gtest.h>

#include <cctype>
#include <vector>

#include "plc_cell/tri/commands.h"
#include "plc_cell/tri/fcs.h"
#include "plc_cell/tri/frame.h"

using namespace plc_cell::tri;

namespace {

std::vector<Decoder::Event> decode(const std::string& bytes, bool wildcard = true) {
  Decoder d(wildcard);
  std::vector<Decoder::Event> out;
  d.feed(bytes, [&](const Decoder::Event& e) { out.push_back(e); });
  return out;
}

Request req(const std::string& body) {
  Request r;
  EXPECT_EQ(parse_request(body, &r), ErrorCode::Ok) << body;
  return r;
}

}  // namespace

TEST(TriFcs, ManualExamples) {
  EXPECT_EQ(fcs_hex("@04RVIA"), "48");  // §15.4.2, worked bit by bit
  EXPECT_EQ(fcs_hex("@01RI02"), "58");
  EXPECT_EQ(fcs(""), 0);
}

TEST(TriFrame, EncodesBothForms) {
  Frame p;
  p.body = "RVD0E10";
  EXPECT_EQ(encode_frame(p), "RVD0E10*\r");
  Frame m;
  m.multipoint = true;
  m.id = 4;
  m.body = "RVIA";
  EXPECT_EQ(encode_frame(m), "@04RVIA48*\r");
  m.id = 1;
  m.body = "RI02";
  EXPECT_EQ(encode_frame(m), "@01RI0258*\r");
}

TEST(TriFrame, DecodesPointToPointAndMultiPoint) {
  auto ev = decode("RVD0E10*\r@04RVIA48*\r");
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].kind, Decoder::Event::FrameReady);
  EXPECT_FALSE(ev[0].frame.multipoint);
  EXPECT_EQ(ev[0].frame.body, "RVD0E10");
  EXPECT_TRUE(ev[1].frame.multipoint);
  EXPECT_EQ(ev[1].frame.id, 4);
  EXPECT_EQ(ev[1].frame.body, "RVIA");
  EXPECT_TRUE(ev[1].fcs_ok);
}

TEST(TriFrame, CtrlEIsReportedAtOnce) {
  auto ev = decode(std::string(1, kEnq) + "IR*\r");
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].kind, Decoder::Event::Enquiry);
  EXPECT_EQ(ev[1].frame.body, "IR");
}

TEST(TriFrame, WildcardFcsAcceptedUnlessRefused) {
  auto ev = decode("@04RVIA00*\r");
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_TRUE(ev[0].fcs_ok);
  EXPECT_TRUE(ev[0].frame.wildcard_fcs);
  ev = decode("@04RVIA00*\r", /*wildcard=*/false);  // SETPROTOCOL n,5
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_FALSE(ev[0].fcs_ok);
  ev = decode("@04RVIA49*\r");
  EXPECT_FALSE(ev[0].fcs_ok);
}

TEST(TriFrame, ByteByByteAndLowerCaseFcs) {
  Decoder d;
  std::vector<Decoder::Event> ev;
  std::string sum = fcs_hex("@0aIR");
  for (char& c : sum) c = char(std::tolower(c));
  const std::string f = "@0aIR" + sum + "*\r";
  for (char c : f) d.feed(std::string(1, c), [&](const Decoder::Event& e) { ev.push_back(e); });
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].frame.id, 10);
  EXPECT_TRUE(ev[0].fcs_ok);
  EXPECT_FALSE(d.in_frame());
}

TEST(TriFrame, FaultsAndResynchronisation) {
  auto ev = decode(std::string("\x01\x02\n", 3) + "RI00\r" + "@ZZIR*\r" + std::string(300, 'A') + "\rRI00*\r");
  ASSERT_EQ(ev.size(), 5u);
  EXPECT_EQ(ev[0].fault, Fault::Garbage);
  EXPECT_EQ(ev[1].fault, Fault::NoTerminator);
  EXPECT_EQ(ev[2].fault, Fault::BadId);
  EXPECT_EQ(ev[3].fault, Fault::TooLong);
  EXPECT_EQ(ev[4].kind, Decoder::Event::FrameReady);
  EXPECT_EQ(ev[4].frame.body, "RI00");
}

TEST(TriCommands, ManualRequestsParse) {
  Request r = req("RVD0E10");
  EXPECT_EQ(r.cmd, Cmd::ReadDm);
  EXPECT_EQ(r.a, 3600u);
  r = req("WVD03E804D2");
  EXPECT_EQ(r.cmd, Cmd::WriteDm);
  EXPECT_EQ(r.a, 1000u);
  EXPECT_EQ(r.values, std::vector<uint32_t>{1234});
  r = req("RVIK");
  EXPECT_EQ(r.cmd, Cmd::ReadInteger);
  EXPECT_EQ(r.a, 10u);
  r = req("wb0100FF");
  EXPECT_EQ(r.cmd, Cmd::ForceBit);
  EXPECT_EQ(r.a, 0x100u);
  EXPECT_EQ(r.values, std::vector<uint32_t>{1});
  EXPECT_EQ(req("Wb010000").values, std::vector<uint32_t>{0});
  r = req("RXI00640A");
  EXPECT_EQ(r.cmd, Cmd::ReadEepromInts);
  EXPECT_EQ(r.a, 100u);
  EXPECT_EQ(r.b, 10u);
  r = req("WVS0801000E");
  EXPECT_EQ(r.cmd, Cmd::WriteSystem);
  EXPECT_EQ(r.a, 8u);
  EXPECT_EQ(r.b, 1u);
  EXPECT_EQ(r.values, std::vector<uint32_t>{14});
  r = req("RVS0902");
  EXPECT_EQ(r.a, 9u);
  EXPECT_EQ(r.b, 2u);
  EXPECT_EQ(req("IR").cmd, Cmd::ReadId);
  r = req("IW0A");
  EXPECT_EQ(r.cmd, Cmd::WriteId);
  EXPECT_EQ(r.a, 10u);
  r = req("RVH2");
  EXPECT_EQ(r.cmd, Cmd::ReadHsc);
  EXPECT_EQ(r.a, 2u);
  r = req("wvH200000000");
  EXPECT_EQ(r.cmd, Cmd::WriteHsc);
  EXPECT_EQ(r.values, std::vector<uint32_t>{0});
  r = req("WVIK00000DD5");  // the manual says 56789; the digits say 0x0DD5 = 3541
  EXPECT_EQ(r.values, std::vector<uint32_t>{3541});
  r = req("WV$P Super PLC");
  EXPECT_EQ(r.cmd, Cmd::WriteString);
  EXPECT_EQ(r.a, 15u);
  EXPECT_EQ(r.text, " Super PLC");
  r = req("RV$M");
  EXPECT_EQ(r.cmd, Cmd::ReadString);
  EXPECT_EQ(r.a, 12u);
  r = req("RA0204");
  EXPECT_EQ(r.cmd, Cmd::ReadAnalog);
  EXPECT_EQ(r.a, 2u);
  EXPECT_EQ(r.b, 4u);
  r = req("RX$000A");
  EXPECT_EQ(r.cmd, Cmd::ReadEepromString);
  EXPECT_EQ(r.a, 10u);
  r = req("WX$000CHello TRi");  // the manual prints it as RX$...; the write is WX$
  EXPECT_EQ(r.cmd, Cmd::WriteEepromString);
  EXPECT_EQ(r.a, 12u);
  EXPECT_EQ(r.text, "Hello TRi");
  r = req("WM0A0123");
  EXPECT_EQ(r.cmd, Cmd::WriteTimerPv);
  EXPECT_EQ(r.a, 10u);
  EXPECT_EQ(r.values, std::vector<uint32_t>{123});
  EXPECT_EQ(req("Wm3F9999").cmd, Cmd::WriteTimerSv);
  EXPECT_EQ(req("Rm00").cmd, Cmd::ReadTimerSv);
  EXPECT_EQ(req("RM00").cmd, Cmd::ReadTimerPv);
  EXPECT_EQ(req("Ru00").cmd, Cmd::ReadCounterSv);
  EXPECT_EQ(req("RU00").cmd, Cmd::ReadCounterPv);
  r = req("WA0102000A0FFF");
  EXPECT_EQ(r.values, (std::vector<uint32_t>{0x000A, 0x0FFF}));
  r = req("WXI0001020001FFFF");
  EXPECT_EQ(r.values, (std::vector<uint32_t>{1, 0xFFFF}));
  EXPECT_EQ(req("C2").cmd, Cmd::Halt);
  EXPECT_EQ(req("C3").cmd, Cmd::Resume);
}

TEST(TriCommands, BadRequestsAreRefusedWithTheirCode) {
  Request r;
  EXPECT_EQ(parse_request("XX00", &r), ErrorCode::UnknownCommand);
  EXPECT_EQ(parse_request("", &r), ErrorCode::UnknownCommand);
  EXPECT_EQ(parse_request("rm00", &r), ErrorCode::UnknownCommand);  // headers are case-sensitive
  EXPECT_EQ(parse_request("RI0", &r), ErrorCode::BadData);
  EXPECT_EQ(parse_request("RI000", &r), ErrorCode::BadData);
  EXPECT_EQ(parse_request("RIG0", &r), ErrorCode::BadData);
  EXPECT_EQ(parse_request("WM00ABCD", &r), ErrorCode::BadData);      // PV is decimal
  EXPECT_EQ(parse_request("wb010012", &r), ErrorCode::BadData);      // FF or 00 only
  EXPECT_EQ(parse_request("WA010200000", &r), ErrorCode::BadData);   // 2 channels, 1.25 words
  EXPECT_EQ(parse_request("RVIa", &r), ErrorCode::BadData);
  EXPECT_EQ(parse_request("IR00", &r), ErrorCode::BadData);
}

TEST(TriCommands, ResponsesBothWays) {
  const Request rvd = req("RVD0E10");
  Response rsp;
  rsp.values = {12345};
  EXPECT_EQ(encode_response(rvd, rsp), "RVD3039");
  const Request rvi = req("RVIK");
  rsp.values = {123456};
  EXPECT_EQ(encode_response(rvi, rsp), "RVI0001E240");
  const Request ri = req("RI00");
  rsp.values = {0xF8};
  EXPECT_EQ(encode_response(ri, rsp), "RIF8");
  const Request rm = req("RM00");
  rsp.values = {42};
  EXPECT_EQ(encode_response(rm, rsp), "RM0042");
  const Request wvd = req("WVD03E804D2");
  EXPECT_EQ(encode_response(wvd, Response{}), "WVD");
  const Request wb = req("Wb010000");
  EXPECT_EQ(encode_response(wb, Response{}), "Wb");  // echoes the header as sent
  Response err;
  err.error = ErrorCode::OutOfRange;
  EXPECT_EQ(encode_response(rvd, err), "ER03");

  // The master side reads them back.
  Response got;
  ASSERT_TRUE(parse_response(rvd, "RVD3039", &got));
  EXPECT_EQ(got.values, std::vector<uint32_t>{12345});
  ASSERT_TRUE(parse_response(rvi, "RVI0001E240", &got));
  EXPECT_EQ(got.values, std::vector<uint32_t>{123456});
  ASSERT_TRUE(parse_response(req("RXI00640A"), "RXI00010002", &got));
  EXPECT_EQ(got.values, (std::vector<uint32_t>{1, 2}));
  ASSERT_TRUE(parse_response(req("RV$M"), "RV$Hello World", &got));
  EXPECT_EQ(got.text, "Hello World");
  ASSERT_TRUE(parse_response(req("IR"), "IR01", &got));
  EXPECT_EQ(got.values, std::vector<uint32_t>{1});
  ASSERT_TRUE(parse_response(rvd, "ER02", &got));
  EXPECT_EQ(got.error, ErrorCode::BadData);
  EXPECT_FALSE(parse_response(rvd, "RVI3039", &got));
  EXPECT_FALSE(parse_response(rvd, "RVD303", &got));
}

TEST(TriCommands, EveryRequestRoundTripsThroughItsEncoding) {
  for (const char* body : {"IR", "IW0A", "RI1F", "RO00", "RR3F", "RT07", "RC00", "RM3F", "Rm00", "RU01", "Ru02",
                           "RVIZ", "RV$A", "RVD0FA0", "RVS0101", "RVH1", "WI0012", "WO01FF", "WR3F00", "WT0701",
                           "WC0080", "WM009999", "Wm010000", "WU020001", "Wu031234", "WVIA80000000", "WV$Btext",
                           "WVD00010001", "WVS09040007", "WVH1FFFFFFFF", "RA0108", "WA01020001FFFF", "RXI0FA020",
                           "RX$0001", "WXI0001010001", "WX$0096forty", "wb05FFFF", "C2", "C3"}) {
    Request r;
    ASSERT_EQ(parse_request(body, &r), ErrorCode::Ok) << body;
    EXPECT_EQ(encode_request(r), body);
  }
}
