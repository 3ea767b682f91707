// Address forms of spec fatek-protocol-and-ports.md 1.7 and the issue's list.
#include <gtest/gtest.h>

#include "plc_cell/core/address.h"
#include "plc_cell/core/error.h"

using namespace plc_cell;

namespace {
Address A(Area a, Width w, uint32_t i) { return Address{a, w, i}; }
std::string why_not(const std::string& text) {
  Address a;
  std::string why;
  EXPECT_FALSE(try_parse_address(text, &a, &why)) << text;
  return why;
}
}  // namespace

TEST(Address, ParsesEveryFormUsersAndProtocolsWrite) {
  EXPECT_EQ(parse_address("X0"), A(Area::X, Width::Bit, 0));
  EXPECT_EQ(parse_address("X0016"), A(Area::X, Width::Bit, 16));
  EXPECT_EQ(parse_address("WX0008"), A(Area::X, Width::Word, 8));
  EXPECT_EQ(parse_address("DWM0000"), A(Area::M, Width::DWord, 0));
  EXPECT_EQ(parse_address("R100"), A(Area::R, Width::Word, 100));
  EXPECT_EQ(parse_address("R00100"), A(Area::R, Width::Word, 100));
  EXPECT_EQ(parse_address("DR4088"), A(Area::R, Width::DWord, 4088));
  EXPECT_EQ(parse_address("D12"), A(Area::D, Width::Word, 12));
  EXPECT_EQ(parse_address("DD12"), A(Area::D, Width::DWord, 12));
  EXPECT_EQ(parse_address("DF00002"), A(Area::F, Width::DWord, 2));
  EXPECT_EQ(parse_address("RT10"), A(Area::RT, Width::Word, 10));
  EXPECT_EQ(parse_address("RC5"), A(Area::RC, Width::Word, 5));
  EXPECT_EQ(parse_address("DRC200"), A(Area::RC, Width::DWord, 200));
  EXPECT_EQ(parse_address("DRT0010"), A(Area::RT, Width::DWord, 10));
  EXPECT_EQ(parse_address("M1911"), A(Area::M, Width::Bit, 1911));
  EXPECT_EQ(parse_address("s999"), A(Area::S, Width::Bit, 999));  // case-insensitive
  EXPECT_EQ(parse_address(" Y5 "), A(Area::Y, Width::Bit, 5));
}

TEST(Address, RangesOfTheFbs) {
  EXPECT_NO_THROW(parse_address("X255"));
  EXPECT_NO_THROW(parse_address("M2001"));
  EXPECT_NO_THROW(parse_address("R8071"));
  EXPECT_NO_THROW(parse_address("D4095"));
  EXPECT_NO_THROW(parse_address("F8191"));
  EXPECT_NO_THROW(parse_address("DR8070"));
  EXPECT_NO_THROW(parse_address("DRC255"));
  EXPECT_NO_THROW(parse_address("WY240"));
  EXPECT_NO_THROW(parse_address("DWY224"));
  for (const char* bad : {"X256", "Y256", "M2002", "S1000", "T256", "C256", "RT256", "RC256", "R8072",
                          "D4096", "F8192", "DR8071", "WY248", "DWY232"})
    EXPECT_NE(why_not(bad).find("out of range"), std::string::npos) << bad;
}

TEST(Address, ErrorsNameTheAddressAndTheReason) {
  EXPECT_NE(why_not("Q5").find("'Q5': unknown prefix"), std::string::npos);
  EXPECT_NE(why_not("WX3").find("multiple of 8"), std::string::npos);
  EXPECT_NE(why_not("DWM4").find("multiple of 8"), std::string::npos);
  EXPECT_NE(why_not("R1x").find("unexpected character 'x'"), std::string::npos);
  EXPECT_NE(why_not("").find("empty"), std::string::npos);
  EXPECT_NE(why_not("R").find("unknown prefix"), std::string::npos);
  EXPECT_NE(why_not("R99999999999").find("too large"), std::string::npos);
  EXPECT_NE(why_not("DRC199").find("32-bit counters"), std::string::npos);
  try {
    parse_address("X999");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "bad address 'X999': out of range: X has elements 0..255");
  }
}

TEST(Address, FormatsShortAndFatekForms) {
  for (const char* s : {"X3", "WY8", "DWM0", "R100", "DR4088", "D12", "DD12", "RT10", "RC5", "DRC200", "DF2"})
    EXPECT_EQ(format_address(parse_address(s)), s);
  EXPECT_EQ(format_fatek_address(parse_address("X16")), "X0016");
  EXPECT_EQ(format_fatek_address(parse_address("WY8")), "WY0008");
  EXPECT_EQ(format_fatek_address(parse_address("R12")), "R00012");
  EXPECT_EQ(format_fatek_address(parse_address("DWM0")), "DWM0000");
  EXPECT_EQ(format_fatek_address(parse_address("DR100")), "DR00100");
  EXPECT_EQ(format_fatek_address(parse_address("DRC200")), "DRC0200");
  EXPECT_EQ(format_fatek_address(parse_address("RT10")), "RT0010");
  EXPECT_EQ(format_fatek_address(parse_address("D3999")), "D03999");
}

TEST(Address, OffsetsStepByElement) {
  // Consecutive W items step by 16 (WY8, WY24 as in the manual's cmd-47 example), DR by 2.
  EXPECT_EQ(offset_address(parse_address("WY8"), 1), parse_address("WY24"));
  EXPECT_EQ(offset_address(parse_address("DWM0"), 2), parse_address("DWM64"));
  EXPECT_EQ(offset_address(parse_address("DR0"), 1), parse_address("DR2"));
  EXPECT_EQ(offset_address(parse_address("DRC200"), 3), parse_address("DRC203"));
  EXPECT_EQ(offset_address(parse_address("X250"), 5), parse_address("X255"));
  EXPECT_THROW(offset_address(parse_address("X250"), 6), Error);
  EXPECT_NO_THROW(check_span(parse_address("R8064"), 8));
  EXPECT_THROW(check_span(parse_address("R8064"), 9), Error);
  EXPECT_THROW(check_span(parse_address("RC198"), 3), Error);  // 16-bit block into C200
  EXPECT_THROW(check_span(parse_address("R0"), 0), Error);
}
