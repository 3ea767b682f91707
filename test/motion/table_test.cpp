// FUN140 motion tables: the manual's text, line-precise errors, register form.
#include <gtest/gtest.h>

#include "motion_fixture.h"
#include "plc_cell/motion/table.h"

namespace plc_cell {
namespace motion {
namespace {


TEST(Table, ManualExample1Parses) {
  Table t;
  TableError e;
  ASSERT_TRUE(parse_table(kExample1, &t, &e)) << e.line << ": " << e.message;
  ASSERT_EQ(t.steps.size(), 4u);
  EXPECT_EQ(t.steps[0].speed.value, 5000);
  EXPECT_EQ(t.steps[0].dir, 1);
  EXPECT_TRUE(t.steps[0].ut);
  EXPECT_EQ(t.steps[0].transfer, Transfer::WaitTime);
  EXPECT_EQ(t.steps[0].time.value, 100);
  EXPECT_EQ(t.steps[1].speed.kind, Operand::R);
  EXPECT_EQ(t.steps[1].stroke.kind, Operand::D);
  EXPECT_EQ(t.steps[1].stroke.value, 100);
  EXPECT_EQ(t.steps[1].time.kind, Operand::R);
  EXPECT_EQ(t.steps[2].dir, -1);
  EXPECT_EQ(t.steps[2].transfer, Transfer::Ext);
  EXPECT_EQ(t.steps[3].stroke.value, 4072);
  EXPECT_FALSE(t.steps[3].ut);
  EXPECT_EQ(t.steps[3].transfer, Transfer::WaitContact);
  EXPECT_EQ(t.steps[3].contact, 1);
  EXPECT_EQ(t.steps[3].goto_kind, Step::Number);
  EXPECT_EQ(t.steps[3].goto_value, 1);
  EXPECT_EQ(encode_table(t).size(), 38u);  // 4 x 9 + 2, as the manual counts
}

TEST(Table, FormatParseAndRegistersRoundTrip) {
  Table t, again, decoded;
  TableError e;
  ASSERT_TRUE(parse_table(kExample1, &t, &e));
  ASSERT_TRUE(parse_table(format_table(t), &again, &e)) << e.line << ": " << e.message << "\n" << format_table(t);
  EXPECT_EQ(again.steps, t.steps);
  const std::vector<uint16_t> r = encode_table(t);
  ASSERT_TRUE(decode_table(r.data(), r.size(), &decoded, &e)) << e.message;
  EXPECT_EQ(decoded.steps, t.steps);
}

TEST(Table, DrvcChainAndDrvzParse) {
  Table t;
  TableError e;
  ASSERT_TRUE(parse_table("SPD 10000\nDRVC ADR,+,20000,Ut\nGOTO NEXT\nSPD 50000\nDRVC ADR,+,60000,Ut\nGOTO NEXT\n"
                          "SPD 3000\nDRV ADR,+,5000,Ut\nWAIT X0\nGOTO 1\nSPD 5000\nDRVZ MD2\nGOTO NEXT\nMEND\n",
                          &t, &e))
      << e.line << ": " << e.message;
  EXPECT_EQ(t.steps[0].motion, Motion::Drvc);
  EXPECT_EQ(t.steps[3].motion, Motion::Drvz);
  EXPECT_EQ(t.steps[3].zero_mode, 2);
}

struct Bad {
  const char* text;
  int code;
  int line;
};

TEST(Table, EveryMalformedLineGivesItsCodeAndLine) {
  const Bad cases[] = {
      {"SPD 0\nDRV ADR,+,1,Ps\nGOTO NEXT\nMEND", 31, 1},                // speed constant 0
      {"SPD 921601\nDRV ADR,+,1,Ps\nGOTO NEXT\nMEND", 31, 1},
      {"SPD R9000\nDRV ADR,+,1,Ps\nGOTO NEXT\nMEND", 30, 1},            // no such register
      {"SPD D4095\nDRV ADR,+,1,Ps\nGOTO NEXT\nMEND", 30, 1},            // 32-bit pair leaves D
      {"SPD Q12\nDRV ADR,+,1,Ps\nGOTO NEXT\nMEND", 30, 1},
      {"SPD 100\nDRV ADR,+,100000000,Ps\nGOTO NEXT\nMEND", 33, 2},      // stroke range
      {"SPD 100\nDRV ADR,+,-5,Ps\nGOTO NEXT\nMEND", 33, 2},
      {"SPD 100\nDRV ADR,+,R8071,Ps\nGOTO NEXT\nMEND", 32, 2},
      {"SPD 100\nDRV ABS,+,5,Ps\nGOTO NEXT\nMEND", 34, 2},              // ABS has no direction
      {"SPD 100\nDRV XYZ,+,5,Ps\nGOTO NEXT\nMEND", 34, 2},
      {"SPD 100\nDRV ADR,*,5,Ps\nGOTO NEXT\nMEND", 34, 2},
      {"SPD 100\nDRV ADR,+,5,mm\nGOTO NEXT\nMEND", 34, 2},
      {"SPD 100\nDRV ADR,+\nGOTO NEXT\nMEND", 34, 2},
      {"SPD 100\nDRVZ MD3\nGOTO NEXT\nMEND", 50, 2},
      {"SPD 100\nWAIT X1\nGOTO NEXT\nMEND", 34, 2},                     // no motion
      {"SPD 100\nDRV ADR,+,5,Ps\nWAIT Z1\nGOTO NEXT\nMEND", 34, 3},
      {"SPD 100\nDRV ADR,+,5,Ps\nWAIT M1912\nGOTO NEXT\nMEND", 34, 3},
      {"SPD 100\nDRV ADR,+,5,Ps\nWAIT Time,70000\nGOTO NEXT\nMEND", 34, 3},
      {"SPD 100\nDRV ADR,+,5,Ps\nEXT X1\nEXT X2\nGOTO NEXT\nMEND", 34, 4},
      {"SPD 100\nDRV ADR,+,5,Ps\nGOTO 2\nMEND", 34, 3},                 // no step 2
      {"SPD 100\nDRV ADR,+,5,Ps\nGOTO SOMEWHERE\nMEND", 34, 3},
      {"SPD 100\nDRV ADR,+,5,Ps\nGOTO NEXT\n", 34, 4},                  // missing MEND
      {"SPD 100\nDRV ADR,+,5,Ps\nMEND", 34, 3},                         // MEND inside a step
      {"SPD 100\nDRV ADR,+,5,Ps\nGOTO NEXT\nMEND\nSPD 5", 34, 5},
      {"MEND", 35, 0},                                                  // no steps
      {"SPD 100\nFLY 3\nGOTO NEXT\nMEND", 34, 2},
      {"002 SPD 100\nDRV ADR,+,5,Ps\nGOTO NEXT\nMEND", 34, 1},          // wrong step number
      // DRVC chains
      {"SPD 1\nDRVC ADR,+,5,Ps\nGOTO NEXT\nSPD 1\nDRVC ABS, ,5,Ps\nGOTO NEXT\nSPD 1\nDRV ADR,+,5,Ps\nGOTO NEXT\nMEND", 41, 4},
      {"SPD 1\nDRVC ADR,+,5,Ps\nGOTO NEXT\nSPD 1\nDRVZ MD0\nGOTO NEXT\nMEND", 42, 4},
      {"SPD 1\nDRVC ADR,+,5,Ps\nGOTO NEXT\nMEND", 34, 1},                // chain must end with DRV
      {"SPD 1\nDRVC ADR, ,5,Ps\nGOTO NEXT\nSPD 1\nDRV ADR,+,5,Ps\nGOTO NEXT\nMEND", 34, 1},
      {"SPD 1\nDRVC ADR,+,5,Ps\nWAIT X1\nGOTO NEXT\nSPD 1\nDRV ADR,+,5,Ps\nGOTO NEXT\nMEND", 34, 1},
      {"SPD 1\nDRVC ADR,+,5,Ps\nGOTO NEXT\nSPD 1\nDRV ADR,-,5,Ps\nGOTO NEXT\nMEND", 34, 4},
  };
  for (const auto& c : cases) {
    Table t;
    t.steps.resize(1);
    TableError e;
    EXPECT_FALSE(parse_table(c.text, &t, &e)) << c.text;
    EXPECT_EQ(e.code, c.code) << c.text << "\n-> " << e.message;
    EXPECT_EQ(e.line, c.line) << c.text << "\n-> " << e.message;
    EXPECT_EQ(t.steps.size(), 1u) << "the output is untouched on error";
  }
}

TEST(Table, NineDrvcsAreTooManySpeeds) {
  std::string s;
  for (int i = 0; i < 8; ++i) s += "SPD 100\nDRVC ADR,+,5,Ps\nGOTO NEXT\n";
  s += "SPD 100\nDRV ADR,+,5,Ps\nGOTO NEXT\nMEND\n";
  Table t;
  TableError e;
  EXPECT_FALSE(parse_table(s, &t, &e));
  EXPECT_EQ(e.code, 34);
  EXPECT_EQ(e.line, 22);  // the eighth DRVC's SPD
}

TEST(Table, MoreThan250StepsIsCode36) {
  std::string s;
  for (int i = 0; i < 251; ++i) s += "SPD 100\nDRV ADR,+,5,Ps\nGOTO NEXT\n";
  s += "MEND\n";
  Table t;
  TableError e;
  EXPECT_FALSE(parse_table(s, &t, &e));
  EXPECT_EQ(e.code, 36);
  EXPECT_EQ(e.line, 751);
}

TEST(Table, BadRegisterImagesAreRejected) {
  Table t, out;
  TableError e;
  ASSERT_TRUE(parse_table(kExample1, &t, &e));
  std::vector<uint16_t> r = encode_table(t);
  auto broken = r;
  broken[1] = 0;
  EXPECT_FALSE(decode_table(broken.data(), broken.size(), &out, &e));
  EXPECT_EQ(e.code, 34);
  broken = r;
  broken[0] = 0;
  EXPECT_FALSE(decode_table(broken.data(), broken.size(), &out, &e));
  EXPECT_EQ(e.code, 35);
  broken = r;
  broken[0] = 251;
  EXPECT_FALSE(decode_table(broken.data(), broken.size(), &out, &e));
  EXPECT_EQ(e.code, 36);
  EXPECT_FALSE(decode_table(r.data(), r.size() - 1, &out, &e));  // truncated
  EXPECT_EQ(e.code, 35);
  broken = r;
  broken[2 + 8] = 7;  // step 1's check word
  EXPECT_FALSE(decode_table(broken.data(), broken.size(), &out, &e));
  EXPECT_EQ(e.code, 34);
  broken = r;
  broken[2 + 2] = 0;  // step 1 speed constant 0
  broken[2 + 3] = 0;
  EXPECT_FALSE(decode_table(broken.data(), broken.size(), &out, &e));
  EXPECT_EQ(e.code, 31);
  // An MMI edit: step 1's stroke 10000 -> 12345 is picked up.
  broken = r;
  broken[2 + 4] = 12345;
  ASSERT_TRUE(decode_table(broken.data(), broken.size(), &out, &e));
  EXPECT_EQ(out.steps[0].stroke.value, 12345);
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell

// The ROS command's homing is a one-step table of the motion layer: DRVZ MDn at the given
// speed, checked as any table (error 31: speed 0; error 50: no MD3).
TEST(Table, HomingIsAOneStepZeroReturnTable) {
  plc_cell::motion::Table t;
  plc_cell::motion::TableError e;
  ASSERT_TRUE(plc_cell::motion::homing_table(5000, 2, &t, &e)) << e.message;
  ASSERT_EQ(t.steps.size(), 1u);
  EXPECT_EQ(t.steps[0].motion, plc_cell::motion::Motion::Drvz);
  EXPECT_EQ(t.steps[0].zero_mode, 2);
  EXPECT_EQ(t.steps[0].speed.value, 5000);
  EXPECT_EQ(t.steps[0].goto_kind, plc_cell::motion::Step::Next);
  EXPECT_FALSE(plc_cell::motion::homing_table(5000, 3, &t, &e));
  EXPECT_EQ(e.code, 50);
  EXPECT_FALSE(plc_cell::motion::homing_table(0, 0, &t, &e));
  EXPECT_EQ(e.code, 31);
}
