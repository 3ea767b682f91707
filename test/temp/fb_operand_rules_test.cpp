// The operand rules of the temperature FUNs (core/operand_rules.h): what `check` warns
// about at load is what turns the FUN's ERR on at run time, one rule for both.
#include <gtest/gtest.h>

#include "fb_cell.h"
#include "plc_cell/core/il_parser.h"
#include "plc_cell/core/operand_rules.h"

namespace plc_cell {
namespace temp {
namespace {

std::vector<Diagnostic> warnings_of(const std::string& program, Generation g = Generation::FB) {
  const FunctionTable t = fb_table(g);
  return operand_warnings(parse_program(program, "p.il", t), t);
}

std::string all(const std::vector<Diagnostic>& ds) {
  std::string s;
  for (const auto& d : ds) s += d.to_string() + "\n";
  return s;
}

const std::string kRest73 = " Ym=Y16 AR=R3842 TR=R0 Yh=Y48 Sv=R100 Os=R120 PR=R140 IR=R160 DR=R180 OR=R300 WR=R200 ERR=M10";
const std::string kEx1Yaml = fb_yaml(
    "      - {type: 2AK4, outputs: Y16, polarity: unipolar, channels: [{temperature: 200}]}\n");

// The cases the issue found passing `check` and refused at run time, and the manual's
// own operands beside them.
struct Case {
  std::string operands;  // Tp Pl Sm Sh Zh
  std::string warning;   // "" for none
};
const std::vector<Case> kFun73 = {
    {"Tp=0 Pl=0 Sm=0 Sh=0 Zh=4", ""},
    {"Tp=2 Pl=3 Sm=0 Sh=0 Zh=4", ""},  // program example 2's PT-100 on -5..5 V
    {"Tp=4 Pl=0 Sm=0 Sh=0 Zh=4", "Tp=4: needs Tp 0 (K), 1 (J), 2 (PT-100) or 3 (PT-1000)"},
    {"Tp=0 Pl=4 Sm=0 Sh=0 Zh=4", "Pl=4: needs Pl 0 (0-10 V), 1 (0-5 V), 2 (-10..10 V) or 3 (-5..5 V)"},
    {"Tp=2 Pl=0 Sm=0 Sh=0 Zh=4", "Tp=2 Pl=0: needs Pl 2 or 3 for an RTD (Tp 2, 3): the FB-2AH(T)4 is bipolar only"},
    {"Tp=0 Pl=0 Sm=2 Sh=0 Zh=4", "Sm=2: needs 0 <= Sm <= 28, a multiple of 4"},
    {"Tp=0 Pl=0 Sm=32 Sh=0 Zh=4", "Sm=32: needs 0 <= Sm <= 28, a multiple of 4"},
    {"Tp=0 Pl=0 Sm=0 Sh=0 Zh=0", "Zh=0: needs 1 <= Zh <= 32 and Sh + Zh <= 32"},
    {"Tp=0 Pl=0 Sm=0 Sh=0 Zh=33", "Zh=33: needs 1 <= Zh <= 32 and Sh + Zh <= 32"},
    {"Tp=0 Pl=0 Sm=0 Sh=30 Zh=4", "Sh=30 Zh=4: needs 1 <= Zh <= 32 and Sh + Zh <= 32"},
    {"Tp=0 Pl=0 Sm=4 Sh=0 Zh=8", "Sm=4 Sh=0 Zh=8: needs Sh >= Sm when Zh > 4 (the TRs of every FUN72/73 contiguous)"},
    {"Tp=0 Pl=0 Sm=4 Sh=0 Zh=4",  // point 1's temperature would be at TR - 4, before R0
     "Sm=4 Sh=0 Zh=4: needs the temperatures of points Sh..Sh+Zh-1 at TR + (Sh - Sm) within the registers"},
};

TEST(OperandRules, Fun73WarnsAtLoadExactlyWhereItSetsErrAtRunTime) {
  for (const Case& k : kFun73) {
    const std::string program = "ORG M3\nLD M1925\nFUN 73 " + k.operands + kRest73 + "\nEND\n";
    const auto ws = warnings_of(program);
    if (k.warning.empty()) {
      EXPECT_TRUE(ws.empty()) << k.operands << "\n" << all(ws);
    } else {
      ASSERT_EQ(ws.size(), 1u) << k.operands << "\n" << all(ws);
      EXPECT_TRUE(ws[0].warning);
      EXPECT_EQ(ws[0].where.line, 3);
      EXPECT_EQ(ws[0].to_string(), "p.il:3:1: warning: FUN 73 TSTC: " + k.warning +
                                       ": at run time the PLC turns its ERR on and the instruction does nothing")
          << k.operands;
    }
    // The run: ERR exactly where the load warned.
    FbCell c(kEx1Yaml, program);
    c.set("M3", 1);
    c.run_to(10000);
    EXPECT_EQ(c.r("M10"), k.warning.empty() ? 0 : 1) << k.operands;
  }
}

TEST(OperandRules, Fun85OnceAndItsRanges) {
  const auto ws = warnings_of(
      "ORG M0\nFUN 85 Tp=0 Pl=0 Zn=25 Yn=Y16 SR=R0 WR=R100 ERR=M1\n"
      "ORG M1\nFUN 85 Tp=2 Pl=0 Zn=24 Yn=Y16 SR=R0 WR=R100 ERR=M2\n"
      "ORG M2\nFUN 85 Tp=0 Pl=0 Zn=24 Yn=Y252 SR=R0 WR=R100 ERR=M3\nEND\n");
  ASSERT_EQ(ws.size(), 5u) << all(ws);
  EXPECT_NE(ws[0].to_string().find("p.il:2:1: warning: FUN 85 TPSNS: Zn=25: needs 1 <= Zn <= 24"), std::string::npos);
  EXPECT_NE(ws[1].to_string().find("p.il:4:1: warning: FUN 85 TPSNS: may be used once in a program, this is use 2 "
                                   "(the first at line 2)"),
            std::string::npos)
      << all(ws);
  EXPECT_NE(ws[2].to_string().find("p.il:4:1: warning: FUN 85 TPSNS: Tp=2: needs Tp 0 (K) or 1 (J)"), std::string::npos);
  EXPECT_NE(ws[3].to_string().find("p.il:6:1: warning: FUN 85 TPSNS: may be used once in a program, this is use 3"),
            std::string::npos);
  EXPECT_NE(ws[4].to_string().find("p.il:6:1: warning: FUN 85 TPSNS: needs Yn: 6 outputs within Y0-Y255"),
            std::string::npos);
}

TEST(OperandRules, Fun72AndTheFbFun86) {
  const auto ws = warnings_of(
      "ORG M0\nFUN 72 Tp=0 Pl=0 Sm=0 Ym=Y16 AR=R100 TR=R0 WR=R100\n"
      "ORG M0\nLD M1925\nFUN 86 Yn=Y30 Sn=20 Zn=5 Sv=R100 Os=R120 PR=R140 IR=R160 DR=R180 OR=R200 WR=R220\n"
      "ORG M0\nLD M1925\nFUN 86 Yn=Y30 Sn=0 Zn=4 Sv=D4094 Os=R120 PR=R140 IR=R160 DR=R180 OR=R200 WR=R220\nEND\n");
  ASSERT_EQ(ws.size(), 3u) << all(ws);
  EXPECT_NE(ws[0].message.find("needs AR: an analog input register R3840-R3903"), std::string::npos) << all(ws);
  EXPECT_NE(ws[1].message.find("Sn=20 Zn=5: needs 1 <= Zn <= 24 and Sn + Zn <= 24"), std::string::npos) << all(ws);
  EXPECT_NE(ws[2].message.find("Zn=4: needs Sv, Os, PR, IR, DR and OR: Zn registers each"), std::string::npos)
      << all(ws);
}

TEST(OperandRules, TheFbsFun86AndFun30) {
  const auto ws = warnings_of(
      "ORG M0\nLD M1925\nFUN 86 Md=2 Yn=Y30 Sn=0 Zn=1 Sv=R100 Os=R120 PR=R140 IR=R160 DR=R180 OR=R200 WR=R220\n"
      "ORG M0\nLD M1925\nFUN 86 Md=0 Yn=Y30 Sn=0 Zn=40 Sv=R100 Os=R120 PR=R140 IR=R160 DR=R180 OR=R200 WR=R220\n"
      "ORG M1\nLD M2\nLD M3\nFUN 30 Ts=0 SR=R0 OR=R10 PR=R20 WR=R30\n"
      "ORG M1\nLD M2\nLD M3\nFUN 30 Ts=R99 SR=R40 OR=R50 PR=R60 WR=R70\nEND\n",  // Ts from a register: at run time
      Generation::FBs);
  ASSERT_EQ(ws.size(), 3u) << all(ws);
  EXPECT_NE(ws[0].message.find("FUN 86 TPCTL: Md=2: needs Md 0 or 1"), std::string::npos) << all(ws);
  EXPECT_NE(ws[1].message.find("Zn=40: needs 1 <= Zn <= 32"), std::string::npos) << all(ws);
  EXPECT_NE(ws[2].message.find("FUN 30 PID: Ts=0: needs 1 <= Ts <= 3000"), std::string::npos) << all(ws);
  EXPECT_EQ(ws[2].where.line, 10);
}

// The manual's worked examples break no rule.
TEST(OperandRules, TheManualsExamplesGiveNoWarning) {
  for (const char* file : {"/examples/temp/fun73_example1.il", "/examples/temp/fb_oven.il"}) {
    const FunctionTable t = fb_table();
    const Program p = load_program_file(std::string(PLC_CELL_SOURCE_DIR) + file, t);
    EXPECT_TRUE(operand_warnings(p, t).empty()) << file << "\n" << all(operand_warnings(p, t));
  }
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
