// Byte-exact vectors of spec 1.9 for every command: requests built and parsed,
// responses built and parsed, and the slave's answers from a real Plc.
#include <gtest/gtest.h>

#include "plc_cell/core/error.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/protocol.h"
#include "plc_cell/fatek/slave.h"

using namespace plc_cell;
using namespace plc_cell::fatek;

namespace {

// "STX 01 40 C7 ETX" written as text with spaces; STX/ETX become 0x02/0x03.
std::string wire(const std::string& text) {
  std::string out;
  std::string tok;
  auto flush = [&] {
    if (tok == "STX") out.push_back('\x02');
    else if (tok == "ETX") out.push_back('\x03');
    else out += tok;
    tok.clear();
  };
  for (char c : text) {
    if (c == ' ') flush();
    else tok.push_back(c);
  }
  flush();
  return out;
}

Frame decode(const std::string& bytes) {
  Decoder d;
  for (size_t i = 0; i < bytes.size(); ++i) {
    const auto s = d.push(uint8_t(bytes[i]));
    if (s == Decoder::Status::Frame) {
      EXPECT_EQ(i, bytes.size() - 1);
      return d.frame();
    }
    EXPECT_NE(s, Decoder::Status::Error) << fault_name(d.fault());
  }
  ADD_FAILURE() << "no frame in " << bytes;
  return {};
}

Request req(Cmd c) {
  Request r;
  r.station = 1;
  r.cmd = c;
  return r;
}

}  // namespace

TEST(FatekFrame, LrcIsThePlainSumFromStx) {
  EXPECT_EQ(lrc(std::string("\x02") + "0140"), 0xC7);
  EXPECT_EQ(encode_frame({1, 0x40, ""}), wire("STX 01 40 C7 ETX"));
  EXPECT_EQ(encode_frame({1, 0x40, ""}), std::string("\x02\x30\x31\x34\x30\x43\x37\x03", 8));
}

TEST(FatekFrame, ResponseLrcZeroIsTwoChars) {
  EXPECT_EQ(encode_frame({1, 0x49, "0"}), wire("STX 01 49 0 00 ETX"));
}

TEST(FatekCodec, Cmd40) {
  EXPECT_EQ(encode_request(req(Cmd::GistStatus)), wire("STX 01 40 C7 ETX"));
  Response rsp;
  std::string why;
  ASSERT_TRUE(parse_response(req(Cmd::GistStatus), decode(wire("STX 01 40 0 29 00 00 22 ETX")), &rsp, &why)) << why;
  EXPECT_EQ(rsp.status, (std::vector<uint8_t>{0x29, 0, 0}));
  rsp.station = 1;
  EXPECT_EQ(encode_response(req(Cmd::GistStatus), rsp), wire("STX 01 40 0 29 00 00 22 ETX"));
}

TEST(FatekCodec, Cmd41) {
  Request r = req(Cmd::RunStop);
  r.run = true;
  EXPECT_EQ(encode_request(r), wire("STX 01 41 1 F9 ETX"));
  r.run = false;
  EXPECT_EQ(encode_request(r), wire("STX 01 41 0 F8 ETX"));
  Request p;
  ASSERT_EQ(parse_request(decode(wire("STX 01 41 1 F9 ETX")), &p), ErrorCode::Ok);
  EXPECT_TRUE(p.run);
  Response rsp;
  std::string why;
  ASSERT_TRUE(parse_response(r, decode(wire("STX 01 41 0 F8 ETX")), &rsp, &why));
  EXPECT_EQ(rsp.error, ErrorCode::Ok);
  ASSERT_TRUE(parse_response(r, decode(wire("STX 01 41 5 FD ETX")), &rsp, &why));
  EXPECT_EQ(rsp.error, ErrorCode::LadderChecksum);
}

TEST(FatekCodec, Cmd42AllActions) {
  struct V {
    Action a;
    const char* addr;
    const char* frame;
  } vs[] = {{Action::Disable, "X16", "STX 01 42 1 X0016 19 ETX"},
            {Action::Enable, "X16", "STX 01 42 2 X0016 1A ETX"},
            {Action::Set, "Y5", "STX 01 42 3 Y0005 1A ETX"},
            {Action::Reset, "Y5", "STX 01 42 4 Y0005 1B ETX"}};
  for (const auto& v : vs) {
    Request r = req(Cmd::Control);
    r.action = v.a;
    r.start = parse_address(v.addr);
    EXPECT_EQ(encode_request(r), wire(v.frame));
    Request p;
    ASSERT_EQ(parse_request(decode(wire(v.frame)), &p), ErrorCode::Ok);
    EXPECT_EQ(p.action, v.a);
    EXPECT_EQ(p.start, r.start);
  }
  Response ok;
  ok.station = 1;
  EXPECT_EQ(encode_response(req(Cmd::Control), ok), wire("STX 01 42 0 F9 ETX"));
}

TEST(FatekCodec, Cmd43) {
  Request r = req(Cmd::ReadEnable);
  r.start = parse_address("Y10");
  r.count = 7;
  EXPECT_EQ(encode_request(r), wire("STX 01 43 07 Y0010 4B ETX"));
  Response rsp;
  std::string why;
  ASSERT_TRUE(parse_response(r, decode(wire("STX 01 43 0 1010001 4D ETX")), &rsp, &why)) << why;
  EXPECT_EQ(rsp.values, (std::vector<uint32_t>{1, 0, 1, 0, 0, 0, 1}));
  EXPECT_EQ(encode_response(r, rsp), wire("STX 01 43 0 1010001 4D ETX"));
}

TEST(FatekCodec, Cmd44) {
  Request r = req(Cmd::ReadDiscretes);
  r.start = parse_address("X50");
  r.count = 6;
  EXPECT_EQ(encode_request(r), wire("STX 01 44 06 X0050 4E ETX"));
  Response rsp;
  std::string why;
  ASSERT_TRUE(parse_response(r, decode(wire("STX 01 44 0 010110 1E ETX")), &rsp, &why)) << why;
  EXPECT_EQ(rsp.values, (std::vector<uint32_t>{0, 1, 0, 1, 1, 0}));
  EXPECT_EQ(encode_response(r, rsp), wire("STX 01 44 0 010110 1E ETX"));
  Request all = req(Cmd::ReadDiscretes);
  all.start = parse_address("M0");
  all.count = 256;
  EXPECT_EQ(encode_request(all), wire("STX 01 44 00 M0000 38 ETX"));
  Request p;
  ASSERT_EQ(parse_request(decode(wire("STX 01 44 00 M0000 38 ETX")), &p), ErrorCode::Ok);
  EXPECT_EQ(p.count, 256u);
}

TEST(FatekCodec, Cmd45) {
  Request r = req(Cmd::WriteDiscretes);
  r.start = parse_address("Y0");
  r.count = 4;
  r.values = {1, 0, 0, 1};
  EXPECT_EQ(encode_request(r), wire("STX 01 45 04 Y0000 1001 0B ETX"));
  Request p;
  ASSERT_EQ(parse_request(decode(wire("STX 01 45 04 Y0000 1001 0B ETX")), &p), ErrorCode::Ok);
  EXPECT_EQ(p.values, r.values);
  Response ok;
  EXPECT_EQ(encode_response(r, ok), wire("STX 01 45 0 FC ETX"));
}

TEST(FatekCodec, Cmd46) {
  Request r = req(Cmd::ReadRegisters);
  r.start = parse_address("R12");
  r.count = 3;
  EXPECT_EQ(encode_request(r), wire("STX 01 46 03 R00012 75 ETX"));
  Response rsp;
  std::string why;
  ASSERT_TRUE(parse_response(r, decode(wire("STX 01 46 0 10A5 7FC4 0001 89 ETX")), &rsp, &why)) << why;
  EXPECT_EQ(rsp.values, (std::vector<uint32_t>{0x10A5, 0x7FC4, 0x0001}));
  EXPECT_EQ(encode_response(r, rsp), wire("STX 01 46 0 10A5 7FC4 0001 89 ETX"));

  Request d = req(Cmd::ReadRegisters);
  d.start = parse_address("DR0");
  d.count = 2;
  EXPECT_EQ(encode_request(d), wire("STX 01 46 02 DR00000 B5 ETX"));
  ASSERT_TRUE(parse_response(d, decode(wire("STX 01 46 0 12345678 0000FFFF 79 ETX")), &rsp, &why)) << why;
  EXPECT_EQ(rsp.values, (std::vector<uint32_t>{0x12345678, 0xFFFF}));
  EXPECT_EQ(encode_response(d, rsp), wire("STX 01 46 0 12345678 0000FFFF 79 ETX"));
  EXPECT_EQ(encode_frame({1, 0x46, "A"}), wire("STX 01 46 A 0E ETX"));
}

TEST(FatekCodec, Cmd47) {
  Request r = req(Cmd::WriteRegisters);
  r.start = parse_address("WY8");
  r.count = 2;
  r.values = {0xAAAA, 0x5555};
  EXPECT_EQ(encode_request(r), wire("STX 01 47 02 WY0008 AAAA 5555 80 ETX"));
  Request p;
  ASSERT_EQ(parse_request(decode(wire("STX 01 47 02 WY0008 AAAA 5555 80 ETX")), &p), ErrorCode::Ok);
  EXPECT_EQ(p.values, r.values);
  EXPECT_EQ(p.start, parse_address("WY8"));
  Response ok;
  EXPECT_EQ(encode_response(r, ok), wire("STX 01 47 0 FE ETX"));
  Request d = req(Cmd::WriteRegisters);
  d.start = parse_address("DR100");
  d.count = 1;
  d.values = {0x12345};
  EXPECT_EQ(encode_request(d), wire("STX 01 47 01 DR00100 00012345 45 ETX"));
}

TEST(FatekCodec, Cmd48) {
  Request r = req(Cmd::MixedRead);
  r.points = {parse_address("R1"), parse_address("Y9"), parse_address("DWM0")};
  EXPECT_EQ(encode_request(r), wire("STX 01 48 03 R00001 Y0009 DWM0000 3F ETX"));
  Request p;
  ASSERT_EQ(parse_request(decode(wire("STX 01 48 03 R00001 Y0009 DWM0000 3F ETX")), &p), ErrorCode::Ok);
  EXPECT_EQ(p.points, r.points);
  Response rsp;
  std::string why;
  ASSERT_TRUE(parse_response(r, decode(wire("STX 01 48 0 5C34 1 003547BA C5 ETX")), &rsp, &why)) << why;
  EXPECT_EQ(rsp.values, (std::vector<uint32_t>{0x5C34, 1, 0x003547BA}));
  EXPECT_EQ(encode_response(r, rsp), wire("STX 01 48 0 5C34 1 003547BA C5 ETX"));
}

TEST(FatekCodec, Cmd49) {
  const char* f = "STX 01 49 04 Y0000 1 Y0001 0 WY0008 5555 DF00002 000000FF 3C ETX";
  Request r = req(Cmd::MixedWrite);
  r.points = {parse_address("Y0"), parse_address("Y1"), parse_address("WY8"), parse_address("DF2")};
  r.values = {1, 0, 0x5555, 0xFF};
  EXPECT_EQ(encode_request(r), wire(f));
  Request p;
  ASSERT_EQ(parse_request(decode(wire(f)), &p), ErrorCode::Ok);
  EXPECT_EQ(p.points, r.points);
  EXPECT_EQ(p.values, r.values);
  Response ok;
  EXPECT_EQ(encode_response(r, ok), wire("STX 01 49 0 00 ETX"));
}

TEST(FatekCodec, Cmd4E) {
  Request r = req(Cmd::Loopback);
  r.text = "ABCDEFG";
  EXPECT_EQ(encode_request(r), wire("STX 01 4E ABCDEFG B8 ETX"));
  Response rsp;
  rsp.text = "ABCDEFG";
  EXPECT_EQ(encode_response(r, rsp), wire("STX 01 4E ABCDEFG B8 ETX"));
  std::string why;
  ASSERT_TRUE(parse_response(r, decode(wire("STX 01 4E ABCDEFG B8 ETX")), &rsp, &why));
  EXPECT_EQ(rsp.text, "ABCDEFG");
}

TEST(FatekCodec, Cmd53) {
  EXPECT_EQ(encode_request(req(Cmd::DetailedStatus)), wire("STX 01 53 CB ETX"));
  const char* f =
      "STX 01 53 0 21 01 02 40 8000 0100 0100 0064 0064 07D2 03E8 0000 1F88 1000 0100 0100 0A ETX";
  Response rsp;
  std::string why;
  ASSERT_TRUE(parse_response(req(Cmd::DetailedStatus), decode(wire(f)), &rsp, &why)) << why;
  ASSERT_EQ(rsp.status.size(), kDetailedStatusBytes);
  EXPECT_EQ(rsp.status[0], 0x21);
  EXPECT_EQ(encode_response(req(Cmd::DetailedStatus), rsp), wire(f));
}

TEST(FatekCodec, MasterRefusesIllegalRequests) {
  Request r = req(Cmd::ReadRegisters);
  r.start = parse_address("R0");
  r.count = 65;
  EXPECT_THROW(encode_request(r), Error);
  r.start = parse_address("DR0");
  r.count = 33;
  EXPECT_THROW(encode_request(r), Error);
  r.count = 32;
  EXPECT_NO_THROW(encode_request(r));
  Request d = req(Cmd::ReadDiscretes);
  d.start = parse_address("M0");
  d.count = 257;
  EXPECT_THROW(encode_request(d), Error);
  Request m = req(Cmd::MixedWrite);
  for (int i = 0; i < 17; ++i) {
    m.points.push_back(parse_address("DR" + std::to_string(2 * i)));
    m.values.push_back(0);
  }
  EXPECT_THROW(encode_request(m), Error);  // weight 34 > 32
  m.points.pop_back();
  m.values.pop_back();
  EXPECT_NO_THROW(encode_request(m));  // weight 32
  Request l = req(Cmd::Loopback);
  l.text = std::string(257, 'A');
  EXPECT_THROW(encode_request(l), Error);
}

TEST(FatekCodec, MixedReadWeightLimit) {
  // Manual example: 20 x 32-bit + 24 discretes/16-bit = weight 64 is one legal cmd 48.
  Request r = req(Cmd::MixedRead);
  for (int i = 0; i < 20; ++i) r.points.push_back(parse_address("DR" + std::to_string(2 * i)));
  for (int i = 0; i < 24; ++i) r.points.push_back(parse_address("Y" + std::to_string(i)));
  const std::string f = encode_request(r);
  Request p;
  ASSERT_EQ(parse_request(decode(f), &p), ErrorCode::Ok);
  EXPECT_EQ(p.points.size(), 44u);
  r.points.push_back(parse_address("Y30"));
  EXPECT_THROW(encode_request(r), Error);
}

TEST(FatekCodec, SlaveParseErrors) {
  Request p;
  auto code = [&](const std::string& data, uint8_t cmd) { return parse_request(Frame{1, cmd, data}, &p); };
  EXPECT_EQ(code("", 0x40), ErrorCode::Ok);
  EXPECT_EQ(code("1", 0x40), ErrorCode::Format);
  EXPECT_EQ(code("2", 0x41), ErrorCode::IllegalValue);
  EXPECT_EQ(code("5X0016", 0x42), ErrorCode::IllegalValue);
  EXPECT_EQ(code("1R00016", 0x42), ErrorCode::Format);
  EXPECT_EQ(code("1X0300", 0x42), ErrorCode::IllegalAddress);
  EXPECT_EQ(code("41R00000", 0x46), ErrorCode::IllegalValue);   // 65 words
  EXPECT_EQ(code("00R00000", 0x46), ErrorCode::IllegalValue);
  EXPECT_EQ(code("21DR00000", 0x46), ErrorCode::IllegalValue);  // 33 DW
  EXPECT_EQ(code("01R09000", 0x46), ErrorCode::IllegalAddress);
  EXPECT_EQ(code("02R08071", 0x46), ErrorCode::IllegalAddress);  // runs past R8071
  EXPECT_EQ(code("01WY0004", 0x46), ErrorCode::IllegalAddress);  // W start not a multiple of 8
  EXPECT_EQ(code("01Q00000", 0x46), ErrorCode::Format);
  EXPECT_EQ(code("01X0000", 0x46), ErrorCode::Format);
  EXPECT_EQ(code("02Y000012", 0x45), ErrorCode::IllegalValue);
  EXPECT_EQ(code("02Y00001", 0x45), ErrorCode::Format);
  EXPECT_EQ(code("01R00000GGGG", 0x47), ErrorCode::Format);
  EXPECT_EQ(code("", 0x50), ErrorCode::Format);  // unknown command
  EXPECT_EQ(code(std::string(257, 'A'), 0x4E), ErrorCode::Format);
}

TEST(FatekCodec, ResponseParseRejectsMismatches) {
  Request r = req(Cmd::ReadRegisters);
  r.start = parse_address("R12");
  r.count = 3;
  Response rsp;
  std::string why;
  EXPECT_FALSE(parse_response(r, Frame{2, 0x46, "0000000000000"}, &rsp, &why));  // other station
  EXPECT_FALSE(parse_response(r, Frame{1, 0x44, "0000000000000"}, &rsp, &why));  // other command
  EXPECT_FALSE(parse_response(r, Frame{1, 0x46, "000000000"}, &rsp, &why));      // short
  EXPECT_FALSE(parse_response(r, Frame{1, 0x46, "0000000000000Z"}, &rsp, &why));  // trailing
  EXPECT_FALSE(parse_response(r, Frame{1, 0x46, "3"}, &rsp, &why));  // no such error code
  ASSERT_TRUE(parse_response(r, Frame{1, 0x46, "A"}, &rsp, &why));
  EXPECT_EQ(rsp.error, ErrorCode::IllegalAddress);
}
