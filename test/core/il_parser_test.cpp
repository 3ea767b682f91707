// Parser errors: every one reported, with file, line, column and a clear message.
#include <gtest/gtest.h>

#include "plc_cell/core/error.h"
#include "plc_cell/core/il_parser.h"

using namespace plc_cell;

namespace {

const FunctionTable& fns() {
  static const FunctionTable t = FunctionTable::with_core_functions();
  return t;
}

std::vector<std::string> errors_of(const std::string& text) {
  try {
    parse_program(text, "p.il", fns());
  } catch (const SourceError& e) {
    std::vector<std::string> out;
    for (const auto& d : e.diagnostics()) out.push_back(d.to_string());
    return out;
  }
  return {};
}

void expect_error(const std::string& text, const std::string& where_and_what) {
  const auto errs = errors_of(text);
  ASSERT_FALSE(errs.empty()) << "no error for:\n" << text;
  bool found = false;
  for (const auto& e : errs) found = found || e.find(where_and_what) != std::string::npos;
  EXPECT_TRUE(found) << "wanted '" << where_and_what << "', got:\n" << errs[0];
}

}  // namespace

TEST(IlParser, AcceptsTheDocumentedForms) {
  const Program p = parse_program(
      "; comment line\n"
      "ORG X0   ; trailing comment\n"
      "AND NOT X1 // also a comment\n"
      "LD TU X2\nOR TD X3\nANDLD\nOUT Y0\nOUT NOT Y1\n"
      "ORG M0\nSET Y2\nRST Y3\nRST R5\nRST DR6\nTMR T0 100\nCTR C0 K10\n"
      "ORG M1\nFUN 8 S=R0 D=R1\nFUN 08DP S=DR0, D=DR2\nMOV.P H10 R3\nFUN 11 ADD Sa=1 Sb=2 D=R4\n"
      "ORG M2\nJMP L1\nLBL L1\nORG M3\nCALL SUB1\nFOR 3\nNEXT\nEND\n"
      "LBL SUB1\nRTS\n",
      "p.il", fns());
  EXPECT_EQ(p.code.size(), 29u);
  EXPECT_EQ(p.labels.count("L1"), 1u);
  EXPECT_EQ(p.labels.count("SUB1"), 1u);
  EXPECT_EQ(p.code[p.main_end].op, Op::End);
  EXPECT_EQ(p.edge_slots, 5u);  // TU, TD, CTR and the two pulse FUNs
  EXPECT_EQ(p.code[16].op, Op::Fun);
  EXPECT_EQ(p.code[16].is32, true);
  EXPECT_EQ(p.code[16].pulse, true);
}

TEST(IlParser, ConstantsInEveryNotation) {
  int64_t v;
  EXPECT_TRUE(parse_constant("123", &v));
  EXPECT_EQ(v, 123);
  EXPECT_TRUE(parse_constant("-5", &v));
  EXPECT_EQ(v, -5);
  EXPECT_TRUE(parse_constant("K77", &v));
  EXPECT_EQ(v, 77);
  EXPECT_TRUE(parse_constant("H1F", &v));
  EXPECT_EQ(v, 31);
  EXPECT_TRUE(parse_constant("0x1f", &v));
  EXPECT_EQ(v, 31);
  EXPECT_TRUE(parse_constant("16#FFFF", &v));
  EXPECT_EQ(v, 65535);
  EXPECT_FALSE(parse_constant("R1", &v));
  EXPECT_FALSE(parse_constant("H", &v));
  EXPECT_FALSE(parse_constant("12a", &v));
}

TEST(IlParser, ErrorsCarryFileLineAndColumn) {
  expect_error("ORG X0\nOUT Q9\nEND\n", "p.il:2:5: error: bad address 'Q9': unknown prefix");
  expect_error("ORG X0\nOUT Y300\nEND\n", "p.il:2:5: error: bad address 'Y300': out of range");
  expect_error("ORG X0\nFROB Y1\nEND\n", "p.il:2:1: error: unknown instruction 'FROB'");
  expect_error("AND X0\nOUT Y0\nEND\n", "p.il:1:1: error: AND has no input: start the network with ORG");
  expect_error("ORG X0\nLD X1\nOUT Y0\nEND\n", "p.il:3:1: error: 1 LD block(s) still open before OUT");
  expect_error("ORG X0\nANDLD\nEND\n", "p.il:2:1: error: ANDLD without a matching LD");
  expect_error("ORG X0\nOUT X1\nEND\n", "OUT cannot drive an input (X1)");
  expect_error("ORG X0\nOUT T1\nEND\n", "driven by TMR/CTR");
  expect_error("ORG X0\nOUT R1\nEND\n", "'R1' is a register");
  expect_error("ORG X0\nTMR C1 10\nEND\n", "TMR needs a timer");
  expect_error("ORG X0\nTMR T1 40000\nEND\n", "p.il:2:8: error: preset 40000 out of range");
  expect_error("ORG X0\nTMR T1\nEND\n", "TMR takes a timer and a preset");
  expect_error("ORG X0\nOUT Y0\n", "the program has no END");
  expect_error("ORG X0\nEND\nEND\n", "second END");
  expect_error("END\nORG X0\nOUT Y0\n", "p.il:2:1: error: code after END must belong to a subroutine");
  expect_error("ORG X0\nJMP nowhere\nEND\n", "p.il:2:5: error: label NOWHERE is not defined");
  expect_error("LBL a\nLBL a\nEND\n", "label a is defined twice (first on line 1)");
  expect_error("ORG X0\nCALL a\nLBL a\nEND\n", "a subroutine must be placed after END");
  expect_error("ORG X0\nRTS\nEND\n", "RTS belongs in the subroutine area after END");
  expect_error("FOR 2\nEND\n", "FOR on line 1 has no NEXT");
  expect_error("NEXT\nEND\n", "NEXT without FOR");
  expect_error("FOR 1\nFOR 1\nFOR 1\nFOR 1\nFOR 1\nFOR 1\nNEXT\nNEXT\nNEXT\nNEXT\nNEXT\nNEXT\nEND\n",
               "FOR nested deeper than 5");
}

TEST(IlParser, FunctionOperandErrors) {
  expect_error("ORG X0\nFUN 999 R0\nEND\n", "p.il:2:5: error: FUN 999 is not available");
  expect_error("ORG X0\nFUN 8 S=R0\nEND\n", "FUN8 MOV needs operand D");
  expect_error("ORG X0\nFUN 8 S=R0 D=R1 R2\nEND\n", "'R2' is one too many");
  expect_error("ORG X0\nFUN 8 S=R0 Q=R1\nEND\n", "FUN8 MOV has no operand 'Q' (operands: S, D)");
  expect_error("ORG X0\nFUN 8 S=R0 S=R1 D=R2\nEND\n", "operand S given twice");
  expect_error("ORG X0\nFUN 8 S=R0 D=5\nEND\n", "'5' is a constant; this operand must be an address");
  expect_error("ORG X0\nMOV S=70000 D=R0\nEND\n", "constant 70000 does not fit in 16 bits (use the .D form)");
  expect_error("ORG X0\nMOV S=DR0 D=R0\nEND\n", "'DR0' is 32-bit; use the .D form");
  expect_error("ORG X0\nMOV S=X0 D=R0\nEND\n", "'X0' is a single discrete");
  expect_error("ORG X0\nMOV.Q S=R0 D=R1\nEND\n", "unknown modifier 'Q'");
  expect_error("ORG X0\nCMP Sa=R0 Sb=R1 EQ=R5\nEND\n", "'R5' must be a discrete");
  expect_error("ORG X0\nCMP Sa=R0 Sb=R1 EQ=X5\nEND\n", "'X5' is an input and cannot be written");
  expect_error("ORG X0\nMUL Sa=R0 Sb=R1 D=R8071\nEND\n", "out of range");  // D needs 2 words
  expect_error("ORG X0\nMOV.D S=0 D=RC199\nEND\n", "32-bit counters");
  expect_error("ORG X0\nMOV S=0 D=RC200\nEND\n", "'RC200' is a 32-bit counter; use the .D form");
}

TEST(IlParser, ReportsEveryErrorNotJustTheFirst) {
  const auto errs = errors_of("ORG X0\nOUT Q1\nAND Z2\nMOV S=R0\nEND\n");
  ASSERT_EQ(errs.size(), 3u);
  EXPECT_NE(errs[0].find("p.il:2:"), std::string::npos);
  EXPECT_NE(errs[1].find("p.il:3:"), std::string::npos);
  EXPECT_NE(errs[2].find("p.il:4:"), std::string::npos);
}

TEST(IlParser, MissingFileIsAnError) {
  try {
    load_program_file("/nonexistent/prog.il", fns());
    FAIL();
  } catch (const SourceError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/prog.il: error: cannot open"), std::string::npos);
  }
}

TEST(IlParser, SurvivesArbitraryBytes) {
  // Random lines must give errors, never crash or hang (the fuzz target does more).
  uint32_t s = 12345;
  const std::string alphabet = "ORGLDANDTMRCTRFUN XYMSTCRDF0123456789=.,;\n\t-+H#";
  for (int round = 0; round < 2000; ++round) {
    std::string text;
    for (int i = 0; i < 60; ++i) {
      s = s * 1664525u + 1013904223u;
      text += alphabet[(s >> 16) % alphabet.size()];
    }
    try {
      parse_program(text, "r.il", fns());
    } catch (const SourceError& e) {
      EXPECT_FALSE(e.diagnostics().empty());
    }
  }
}
