// FUN147 interpolation tables: the manual's example C, line-precise errors, the
// N x 15 + 2 register form.
#include <gtest/gtest.h>

#include "motion_fixture.h"
#include "plc_cell/motion/lin_table.h"

namespace plc_cell {
namespace motion {
namespace {

TEST(LinTable, ManualExampleCParses) {
  LinTable t;
  TableError e;
  ASSERT_TRUE(parse_lin_table(kExampleC, &t, &e)) << e.line << ": " << e.message;
  ASSERT_EQ(t.steps.size(), 3u);
  const LinStep& s1 = t.steps[0];
  EXPECT_EQ(s1.flow.speed.value, 5000);
  EXPECT_FALSE(s1.line);
  EXPECT_FALSE(s1.abs);
  EXPECT_TRUE(s1.ut);
  EXPECT_EQ(s1.axes, 0xF);  // all four axes
  EXPECT_EQ(s1.stroke[0].value, 500);
  EXPECT_EQ(s1.stroke[3].value, 200);
  EXPECT_EQ(s1.flow.transfer, Transfer::WaitTime);
  EXPECT_EQ(s1.flow.time.value, 100);  // 1 s
  const LinStep& s2 = t.steps[1];
  EXPECT_EQ(s2.flow.speed.kind, Operand::R);
  EXPECT_EQ(s2.axes, 0x3);  // "D100,D200, , ": Ps2 and Ps3 blank
  EXPECT_EQ(s2.stroke[1].kind, Operand::D);
  EXPECT_EQ(s2.stroke[1].value, 200);
  EXPECT_EQ(s2.flow.time.kind, Operand::R);
  const LinStep& s3 = t.steps[2];
  EXPECT_EQ(s3.axes, 0xC);  // "0,0,R300,R400": Ps0 and Ps1 inactive
  EXPECT_FALSE(s3.ut);
  EXPECT_EQ(s3.flow.transfer, Transfer::WaitContact);
  EXPECT_EQ(s3.flow.goto_kind, Step::Number);
  EXPECT_EQ(t.axes(), 0xF);
  EXPECT_EQ(encode_lin_table(t).size(), 47u);  // 3 x 15 + 2, as the manual counts
}

TEST(LinTable, FormatParseAndRegistersRoundTrip) {
  LinTable t, again, decoded;
  TableError e;
  const std::string text = std::string(kExampleC) ;
  ASSERT_TRUE(parse_lin_table(text, &t, &e));
  ASSERT_TRUE(parse_lin_table(format_lin_table(t), &again, &e)) << e.line << ": " << e.message << "\n"
                                                                 << format_lin_table(t);
  EXPECT_EQ(again.steps, t.steps);
  const std::vector<uint16_t> r = encode_lin_table(t);
  EXPECT_EQ(r[0], 3u);
  EXPECT_EQ(r[1], kLinTableMagic);
  ASSERT_TRUE(decode_lin_table(r.data(), r.size(), &decoded, &e)) << e.message;
  EXPECT_EQ(decoded.steps, t.steps);
  // The documented layout: step 1 at SR+2, its Ps1 stroke at +6/+7, check word +14.
  EXPECT_EQ(r[2 + 0] & 0xF0, 0xF0);  // axis mask
  EXPECT_EQ(r[2 + 6], 400u);
  EXPECT_EQ(r[2 + 14], 1u);
  EXPECT_EQ(r[2 + 15 + 14], 2u);
}

TEST(LinTable, LineChainAndAbsParse) {
  LinTable t;
  TableError e;
  ASSERT_TRUE(parse_lin_table("SPD 1000\nLINE ADR,100,100, , ,Ps\nGOTO NEXT\nSPD 2000\nLIN ABS,0, , ,-50\nEXT X3\nGOTO 1\nMEND\n",
                              &t, &e))
      << e.line << ": " << e.message;
  EXPECT_TRUE(t.steps[0].line);
  EXPECT_TRUE(t.steps[1].abs);
  EXPECT_EQ(t.steps[1].axes, 0x9);  // ABS 0 is a target (position 0), blank is inactive
  EXPECT_FALSE(t.steps[1].ut);      // resolution omitted: Ps
  EXPECT_EQ(t.steps[1].flow.transfer, Transfer::Ext);
}

struct Bad {
  const char* text;
  int code, line;
};

TEST(LinTable, EveryMalformedLineGivesItsCodeAndLine) {
  const Bad cases[] = {
      {"SPD 0\nLIN ADR,1,1,1,1,Ps\nGOTO NEXT\nMEND\n", 31, 1},          // speed constant out of range
      {"SPD 921601\nLIN ADR,1, , , ,Ps\nGOTO NEXT\nMEND\n", 31, 1},
      {"SPD R9000\nLIN ADR,1, , , ,Ps\nGOTO NEXT\nMEND\n", 30, 1},       // speed register out of range
      {"SPD X1\nLIN ADR,1, , , ,Ps\nGOTO NEXT\nMEND\n", 30, 1},
      {"SPD 100\nLIN ADR,1,100000000, , ,Ps\nGOTO NEXT\nMEND\n", 33, 2},  // stroke beyond 99999999
      {"SPD 100\nLIN ADR,1, ,D4095, ,Ps\nGOTO NEXT\nMEND\n", 32, 2},      // the pair D4095/D4096 does not fit
      {"SPD 100\nLIN ADR,1, ,Q5, ,Ps\nGOTO NEXT\nMEND\n", 32, 2},
      {"SPD 100\nLIN ADR,1,2,3\nGOTO NEXT\nMEND\n", 60, 2},               // too few operands
      {"SPD 100\nLIN ADR,1,2,3,4,5,Ps\nGOTO NEXT\nMEND\n", 60, 2},        // too many
      {"SPD 100\nLIN REL,1,2,3,4,Ps\nGOTO NEXT\nMEND\n", 60, 2},          // coordinate
      {"SPD 100\nLIN ADR,1,2,3,4,mm\nGOTO NEXT\nMEND\n", 60, 2},          // resolution
      {"SPD 100\nLIN ADR,0, ,0, ,Ps\nGOTO NEXT\nMEND\n", 60, 2},          // no axis moves
      {"SPD 100\nDRV ADR,+,5,Ps\nGOTO NEXT\nMEND\n", 60, 2},              // a FUN140 command
      {"SPD 100\nLIN ADR,5, , , \nACT Time,10\nGOTO NEXT\nMEND\n", 60, 3}, // ACT is not a FUN147 condition
      {"SPD 100\nLIN ADR,5, , , \nGOTO NEXT\nMEND\nSPD 5\n", 34, 5},      // text after MEND
      {"SPD 100\nGOTO NEXT\nMEND\n", 34, 2},                              // no LIN
      {"LIN ADR,5, , , \nGOTO NEXT\nMEND\n", 34, 1},                      // LIN before SPD
      {"SPD 100\nLIN ADR,5, , , \nLIN ADR,5, , , \nGOTO NEXT\nMEND\n", 34, 3},
      {"SPD 100\nLIN ADR,5, , , \nWAIT Z1\nGOTO NEXT\nMEND\n", 34, 3},    // contact
      {"SPD 100\nLIN ADR,5, , , \nGOTO 2\nMEND\n", 34, 3},                // no step 2
      {"SPD 100\nLIN ADR,5, , , \nGOTO NEXT\n", 34, 4},                   // missing MEND
      {"SPD 100\nLIN ADR,5, , , \nFOO 1\nGOTO NEXT\nMEND\n", 34, 3},      // unknown command
      {"002 SPD 100\nLIN ADR,5, , , \nGOTO NEXT\nMEND\n", 34, 1},         // wrong step number
      {"SPD 100\nLINE ADR,5, , , \nWAIT X0\nGOTO NEXT\nSPD 10\nLIN ADR,5, , , \nGOTO NEXT\nMEND\n", 34, 1},
      {"SPD 100\nLINE ADR,5, , , \nGOTO 1\nSPD 10\nLIN ADR,5, , , \nGOTO NEXT\nMEND\n", 34, 1},
      {"SPD 100\nLINE ADR,5, , , \nGOTO NEXT\nMEND\n", 34, 1},            // a LINE chain must end with LIN
      {"MEND\n", 35, 0},                                                  // no steps
  };
  for (const auto& c : cases) {
    LinTable t;
    TableError e;
    EXPECT_FALSE(parse_lin_table(c.text, &t, &e)) << c.text;
    EXPECT_EQ(e.code, c.code) << c.text << "\n" << e.message;
    EXPECT_EQ(e.line, c.line) << c.text << "\n" << e.message;
    EXPECT_FALSE(e.message.empty());
    EXPECT_TRUE(t.steps.empty());  // the output is left untouched
  }
}

TEST(LinTable, BadRegisterImagesAreRejected) {
  LinTable t;
  TableError e;
  ASSERT_TRUE(parse_lin_table(kExampleC, &t, &e));
  const std::vector<uint16_t> good = encode_lin_table(t);
  struct Corrupt {
    size_t at;
    uint16_t value;
    int code;
  };
  const Corrupt cases[] = {
      {1, 0x140A, 34},           // a FUN140 table's magic
      {0, 0, 35},                // no steps
      {0, 251, 36},              // over the maximum
      {0, 4, 35},                // 4 steps do not fit in 47 words
      {2 + 14, 7, 34},           // check word
      {2 + 0, 0x00F8, 60},       // reserved bit 3
      {2 + 1, 0x3000, 34},       // operand kinds beyond the six fields
      {2 + 2, 0, 31},            // speed constant 0
      {2 + 4, 0xFFFF, 33},       // Ps0 stroke 0x0000FFFF... with high word below
      {2 + 0, 0x03F0, 60},       // ACT transfer (3)
      {2 + 15 + 13, 9, 34},      // GOTO is NEXT in step 2: ignored -> use step 3's GOTO 1 instead
  };
  for (const auto& c : cases) {
    std::vector<uint16_t> r = good;
    r[c.at] = c.value;
    if (c.code == 33) r[c.at + 1] = 0x7FFF;  // 0x7FFFFFFF: beyond 99999999
    if (c.at == 2 + 15 + 13) {                // step 3's GOTO 1 -> 9
      r[c.at] = good[c.at];
      r[2 + 30 + 13] = 9;
    }
    LinTable out;
    TableError err;
    EXPECT_FALSE(decode_lin_table(r.data(), c.code == 35 && c.value == 4 ? 47 : r.size(), &out, &err)) << c.at;
    EXPECT_EQ(err.code, c.code) << "word " << c.at << ": " << err.message;
  }
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell
