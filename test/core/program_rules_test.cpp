// The rules of docs/program-format.md "Rules the manual leaves open" and "Areas", one test
// each, on the interpreter. Expected values are worked out by hand next to each assertion;
// where the manual (FBs-PLC Manual II) decides, the test names the section.
#include <fstream>

#include "plc_cell/core/error.h"
#include "plc_cell/core/il_parser.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/sim/soft_cell.h"
#include "plc_fixture.h"
#include "run_tool.h"

using namespace plc_cell;

namespace {

// Errors of a program under a function table, as "file:line:col: error: message" lines.
std::string errors_of(const std::string& text, const FunctionTable& fns = FunctionTable::with_core_functions()) {
  try {
    parse_program(text, "p.il", fns);
  } catch (const SourceError& e) {
    std::string out;
    for (const auto& d : e.diagnostics()) out += d.to_string() + "\n";
    return out;
  }
  return "";
}

// A core table plus FUN 240 TWOIN with inputs EN and PAU: it copies PAU to its flag, so a
// test sees that both inputs reached it.
FunctionTable with_two_inputs() {
  FunctionTable t = FunctionTable::with_core_functions();
  FunctionSpec s;
  s.number = 240;
  s.mnemonic = "TWOIN";
  s.inputs = {"EN", "PAU"};
  s.operands = {{"F", OperandRole::BitOut}};
  s.always_runs = true;
  s.handler = [](ExecContext& c, const BoundOperand* o) { c.flag(o[0], c.inputs[1]); };
  t.add(s);
  return t;
}

class ProgramRules : public BothEnginesFixture {};
PLC_CELL_ON_BOTH_ENGINES(ProgramRules);

class TwoInputRules : public BothEnginesFixture {
 protected:
  TwoInputRules() : BothEnginesFixture(with_two_inputs()) {}
};
PLC_CELL_ON_BOTH_ENGINES(TwoInputRules);

}  // namespace

// ---- Areas and FOR ---------------------------------------------------------------

TEST_P(ProgramRules, JmpStaysInItsAreaAndMayReachAnyLabelAfterEnd) {
  EXPECT_NE(errors_of("ORG M1925\nJMP sub\nEND\nLBL sub\nRTS\n").find("p.il:2:5: error: JMP SUB crosses"),
            std::string::npos);
  EXPECT_NE(errors_of("LBL top\nORG M1925\nCALL s\nEND\nLBL s\nORG M1925\nJMP top\nRTS\n").find("p.il:7:5: error: JMP TOP crosses"),
            std::string::npos);
  // CALL a; a jumps to c, which another CALL could enter; c's RTS returns after the CALL.
  // Each scan: R1 +1 (in c), R0 untouched (skipped in a), R2 +1 (main after the CALL).
  load("ORG M1925\nCALL a\nORG M1925\nINC R2\nEND\n"
       "LBL a\nORG M1925\nJMP c\nORG M1925\nINC R0\nRTS\n"
       "LBL c\nORG M1925\nINC R1\nRTS\n");
  scans(3);
  EXPECT_EQ(get("R0"), 0u);
  EXPECT_EQ(get("R1"), 3u);
  EXPECT_EQ(get("R2"), 3u);
}

TEST_P(ProgramRules, ALabelInsideAForBodyIsAcceptedInBothAreas) {
  // The same FOR body with a label inside, in the main program and in a routine.
  EXPECT_EQ(errors_of("FOR 2\nLBL in_main\nORG M1925\nINC R0\nNEXT\nEND\n"), "");
  EXPECT_EQ(errors_of("ORG M1925\nCALL s\nEND\nLBL s\nFOR 2\nLBL in_sub\nORG M1925\nINC R0\nNEXT\nRTS\n"), "");
  // A FOR left open after END is still reported, at the end of the file.
  EXPECT_NE(errors_of("ORG M1925\nCALL s\nEND\nLBL s\nFOR 2\nORG M1925\nINC R0\nRTS\n").find("FOR on line 5 has no NEXT"),
            std::string::npos);
  // Run: the routine's body jumps back to its inner label while R1 < 3 (so 3 passes of
  // the jump loop in the first iteration), then the FOR's second iteration adds one more:
  // R0 = 3 + 1 = 4 after one scan.
  load("ORG M1925\nCALL s\nEND\n"
       "LBL s\nFOR 2\nLBL again\nORG M1925\nINC R0\nINC R1\nFUN 17 CMP Sa=R1 Sb=3 LT=M0\nORG M0\nJMP again\nNEXT\nRTS\n");
  scans(1);
  EXPECT_EQ(get("R0"), 4u);
}

TEST_P(ProgramRules, ForReadsItsCountOnce) {
  // R5 = 3 at the first FOR; the body sets R5 = 10: this scan still loops 3 times, the next 10.
  load("ORG M1925\nFOR R5\nORG M1925\nINC R0\nMOV S=10 D=R5\nNEXT\nEND\n");
  put("R5", 3);
  scans(1);
  EXPECT_EQ(get("R0"), 3u);
  scans(1);
  EXPECT_EQ(get("R0"), 13u);
  // 40000 in R5 reads -25536: the body is skipped.
  put("R5", 40000);
  scans(1);
  EXPECT_EQ(get("R0"), 13u);
}

// ---- One network result ------------------------------------------------------------

TEST_P(ProgramRules, TmrCtrAndFunPassTheNetworkResultOn) {
  // T0 needs 5 x 10 ms, C0 3 edges: at the first scan with X0 on neither is on, yet the
  // coils after them follow X0.
  load("ORG X0\nTMR T0 5\nOUT Y0\nCTR C0 3\nOUT Y1\nMOV S=7 D=R0\nOUT Y2\nEND\n");
  input(0, true);
  scans(1, 10000);
  EXPECT_EQ(get("T0"), 0u);
  EXPECT_EQ(get("C0"), 0u);
  EXPECT_EQ(get("Y0"), 1u);
  EXPECT_EQ(get("Y1"), 1u);
  EXPECT_EQ(get("Y2"), 1u);
  EXPECT_EQ(get("R0"), 7u);
  input(0, false);
  scans(1, 10000);
  EXPECT_EQ(get("Y0"), 0u);
  EXPECT_EQ(get("Y1"), 0u);
  EXPECT_EQ(get("Y2"), 0u);
}

TEST_P(TwoInputRules, AFunWithSeveralInputsLeavesItsEnAsTheResult) {
  load("ORG X0\nLD X1\nFUN 240 F=M0\nOUT Y0\nEND\n");
  input(0, true);
  input(1, false);
  scans(1);
  EXPECT_EQ(get("Y0"), 1u);  // EN (X0), not PAU (X1)
  EXPECT_EQ(get("M0"), 0u);  // PAU reached the function
  input(0, false);
  input(1, true);
  scans(1);
  EXPECT_EQ(get("Y0"), 0u);
  EXPECT_EQ(get("M0"), 1u);
}

// ---- Edge results ------------------------------------------------------------------

TEST_P(ProgramRules, ShiftCountsAtOrBeyondTheWidthAndNotPositive) {
  load("ORG M1925\nSHL D=R0 N=R10 OTB=M0\nSHR D=R1 N=R10 OTB=M1\nEND\n");
  const auto run = [&](uint32_t n) {
    put("R0", 0x2001);
    put("R1", 0x8001);
    put("M0", 1);
    put("M1", 1);
    put("R10", n);
    scans(1);
  };
  run(3);  // H2001 << 3 = H0008, last out bit 13 = 1; H8001 >> 3 = H1000, last out bit 2 = 0
  EXPECT_EQ(get("R0"), 0x0008u);
  EXPECT_EQ(get("M0"), 1u);
  EXPECT_EQ(get("R1"), 0x1000u);
  EXPECT_EQ(get("M1"), 0u);
  run(16);  // everything out: SHL's last bit out is bit 0 (1), SHR's bit 15 (1)
  EXPECT_EQ(get("R0"), 0u);
  EXPECT_EQ(get("M0"), 1u);
  EXPECT_EQ(get("R1"), 0u);
  EXPECT_EQ(get("M1"), 1u);
  run(17);  // past the width: the last bit out is a shifted-in 0
  EXPECT_EQ(get("R0"), 0u);
  EXPECT_EQ(get("M0"), 0u);
  EXPECT_EQ(get("R1"), 0u);
  EXPECT_EQ(get("M1"), 0u);
  run(0);  // nothing shifted: D and OTB unchanged
  EXPECT_EQ(get("R0"), 0x2001u);
  EXPECT_EQ(get("M0"), 1u);
  run(0xFFFF);  // -1
  EXPECT_EQ(get("R0"), 0x2001u);
  EXPECT_EQ(get("M0"), 1u);
  EXPECT_EQ(get("R1"), 0x8001u);
  EXPECT_EQ(get("M1"), 1u);
}

TEST_P(ProgramRules, DivisionTruncatesTowardZeroAndMinusOneOverflowWraps) {
  load("ORG M1925\n"
       "DIV Sa=-7 Sb=2 D=R0 ERR=M0\n"
       "DIV Sa=7 Sb=-2 D=R2 ERR=M1\n"
       "DIV Sa=-32768 Sb=-1 D=R4 ZR=M2 ERR=M3\n"
       "DIV.D Sa=DR20 Sb=-1 D=R6 ZR=M4 ERR=M5\n"
       "END\n");
  put("DR20", 0x80000000u);  // -2^31
  scans(1);
  EXPECT_EQ(sget("R0"), -3);  // -7 / 2 = -3 remainder -1
  EXPECT_EQ(sget("R1"), -1);
  EXPECT_EQ(sget("R2"), -3);  // 7 / -2 = -3 remainder 1
  EXPECT_EQ(sget("R3"), 1);
  EXPECT_EQ(get("R4"), 0x8000u);  // 32768 does not fit: its bit pattern, -32768
  EXPECT_EQ(get("R5"), 0u);
  EXPECT_EQ(get("M2"), 0u);
  EXPECT_EQ(get("M3"), 0u);
  EXPECT_EQ(get("DR6"), 0x80000000u);  // 2^31 as its bit pattern
  EXPECT_EQ(get("DR8"), 0u);
  EXPECT_EQ(get("M4") + get("M5"), 0u);
  EXPECT_EQ(get("M0") + get("M1"), 0u);
}

TEST_P(ProgramRules, RegisterPresetsZeroOrNegativeAreReachedAtOnce) {
  load("ORG X0\nTMR T0 R0\nORG X1\nCTR C0 R1\nCTR C1 R2\nEND\n");
  put("R0", 0xFFFB);  // -5
  put("R1", 40000);   // reads -25536
  put("R2", 0);
  scans(1, 10000);
  EXPECT_EQ(get("T0"), 0u);  // the timer's input is off
  EXPECT_EQ(get("C0"), 1u);  // on at the execution, without an edge
  EXPECT_EQ(get("C1"), 1u);
  input(0, true);
  scans(1, 10000);
  EXPECT_EQ(get("T0"), 1u);
  EXPECT_EQ(get("RT0"), 0u);
  for (int i = 0; i < 3; ++i) {
    input(1, true);
    scans(1, 10000);
    input(1, false);
    scans(1, 10000);
  }
  EXPECT_EQ(get("RC0"), 0u);  // the value does not move
  EXPECT_EQ(get("RC1"), 0u);
  input(0, false);
  scans(1, 10000);
  EXPECT_EQ(get("T0"), 0u);
}

TEST_P(ProgramRules, ThirtyTwoBitCountersReadAPairPreset) {
  EXPECT_NE(errors_of("ORG X0\nCTR C0 DR0\nEND\n").find("p.il:2:8: error: 'DR0' is 32-bit; C0 takes a 16-bit preset"),
            std::string::npos);
  EXPECT_NE(errors_of("ORG X0\nTMR T0 DR0\nEND\n").find("'DR0' is 32-bit; T0 takes a 16-bit preset"), std::string::npos);
  // Constant presets: 0..2147483647 for C200-C255 (3000000000 would read negative).
  EXPECT_EQ(errors_of("ORG X0\nCTR C200 2147483647\nEND\n"), "");
  EXPECT_NE(errors_of("ORG X0\nCTR C200 3000000000\nEND\n").find("p.il:2:10: error: preset 3000000000 out of range (0..2147483647)"),
            std::string::npos);
  // DR0 = H00010000 = 65536: R0 alone would read 0 and turn C200 on at once.
  load("ORG X0\nCTR C200 DR0\nORG X0\nCTR C201 R0\nEND\n");
  put("DR0", 0x00010000u);
  for (int i = 0; i < 3; ++i) {
    input(0, true);
    scans(1);
    input(0, false);
    scans(1);
  }
  EXPECT_EQ(get("DRC200"), 3u);
  EXPECT_EQ(get("C200"), 0u);
  EXPECT_EQ(get("DRC201"), 3u);
  EXPECT_EQ(get("C201"), 0u);
  put("DR0", 3);  // now reached
  scans(1);
  EXPECT_EQ(get("C200"), 1u);
  EXPECT_EQ(get("C201"), 1u);
}

TEST_P(ProgramRules, ATmrRunTwiceAScanAddsTheScanTimeTwice) {
  // T0: 0.01 s base, preset 100 (1 s); 10 ms scans; the FOR runs TMR twice a scan.
  // First scan with X0 on: starts (0), then +1; each later scan +2: RT0 = 2k - 1 after k
  // scans, so 99 after 50 scans and the preset (101 clamped to 100) at the 51st: 0.51 s, not 1 s.
  load("ORG M1925\nFOR 2\nORG X0\nTMR T0 100\nNEXT\nEND\n");
  scans(1, 10000);  // a first scan, so that the next one has 10 ms behind it
  input(0, true);
  scans(50, 10000);
  EXPECT_EQ(get("RT0"), 99u);
  EXPECT_EQ(get("T0"), 0u);
  scans(1, 10000);
  EXPECT_EQ(get("RT0"), 100u);
  EXPECT_EQ(get("T0"), 1u);
}

TEST_P(ProgramRules, FunWritesToRtAndRcAreCarriedOn) {
  // T0: 0.01 s base, preset 10; 10 ms scans. Scans 1-2: RT0 0, 1. Scan 3: TMR makes 2,
  // then MOV.P writes 8 (T0 was compared before: off). Scan 4: 9, off. Scan 5: 10, on.
  load("ORG X0\nTMR T0 10\nORG X1\nMOV.P S=8 D=RT0\n"
       "ORG X2\nCTR C0 5\nORG X3\nMOV.P S=4 D=RC0\nEND\n");
  input(0, true);
  scans(2, 10000);
  EXPECT_EQ(get("RT0"), 1u);
  input(1, true);
  scans(1, 10000);
  EXPECT_EQ(get("RT0"), 8u);
  EXPECT_EQ(get("T0"), 0u);
  scans(1, 10000);
  EXPECT_EQ(get("RT0"), 9u);
  EXPECT_EQ(get("T0"), 0u);
  scans(1, 10000);
  EXPECT_EQ(get("T0"), 1u);
  // RC0 = 4 written, then one edge: 5 = the preset.
  input(3, true);
  scans(1, 10000);
  EXPECT_EQ(get("RC0"), 4u);
  EXPECT_EQ(get("C0"), 0u);
  input(2, true);
  scans(1, 10000);
  EXPECT_EQ(get("RC0"), 5u);
  EXPECT_EQ(get("C0"), 1u);
}

// ---- Syntax --------------------------------------------------------------------------

TEST_P(ProgramRules, WViewsAsMulAndDivDestinationsSpanTwoWords) {
  EXPECT_NE(errors_of("ORG M1925\nMUL Sa=1 Sb=1 D=WY248\nEND\n").find("p.il:2:"), std::string::npos);
  load("ORG M1925\nMUL Sa=300 Sb=300 D=WY0\nDIV Sa=100 Sb=7 D=WM0\nEND\n");
  scans(1);
  EXPECT_EQ(get("WY0"), 0x5F90u);  // 90000 = H00015F90
  EXPECT_EQ(get("WY16"), 0x0001u);
  EXPECT_EQ(get("WM0"), 14u);  // 100 / 7 = 14 remainder 2
  EXPECT_EQ(get("WM16"), 2u);
}

TEST_P(ProgramRules, FunNumberMnemonicAndModifiers) {
  EXPECT_EQ(errors_of("ORG M1925\nFUN 8 MOV.D S=DR0 D=DR2\nFUN 8D MOV S=DR0 D=DR4\nFUN 8P MOV S=R0 D=R1\n"
                      "FUN 8 MOV.DP S=DR0 D=DR6\nEND\n"),
            "");
  EXPECT_NE(errors_of("ORG M1925\nFUN 8D MOV.D S=DR0 D=DR2\nEND\n").find("p.il:2:8: error: modifiers given twice"),
            std::string::npos);
  EXPECT_NE(errors_of("ORG M1925\nFUN 8 ADD Sa=R0 Sb=R1 D=R2\nEND\n").find("p.il:2:7: error: FUN 8 is MOV; ADD is FUN 11"),
            std::string::npos);
  load("ORG M1925\nFUN 8 MOV.D S=70000 D=DR2\nEND\n");
  scans(1);
  EXPECT_EQ(get("DR2"), 70000u);
}

TEST_P(ProgramRules, PositionalOperandsAfterABareMnemonicAndMixed) {
  load("ORG M1925\nMOV R0 R10\nADD R0 5 R2 M0\nADD D=R3 R0 -5 ZR=M1\nEND\n");
  put("R0", 5);
  scans(1);
  EXPECT_EQ(get("R10"), 5u);
  EXPECT_EQ(get("R2"), 10u);  // 5 + 5
  EXPECT_EQ(get("M0"), 0u);
  EXPECT_EQ(get("R3"), 0u);  // D named, then Sa = R0, Sb = -5: 5 - 5 = 0, ZR on
  EXPECT_EQ(get("M1"), 1u);
}

TEST_P(ProgramRules, ConstantSigns) {
  EXPECT_NE(errors_of("ORG M1925\nMOV S=-K5 D=R0\nEND\n").find("p.il:2:7: error: '-K5': the sign goes after K (K-5)"),
            std::string::npos);
  EXPECT_NE(errors_of("ORG M1925\nMOV S=H-5 D=R0\nEND\n").find("p.il:2:7: error: 'H-5': a hexadecimal constant has no sign"),
            std::string::npos);
  EXPECT_NE(errors_of("ORG M1925\nMOV S=K65536 D=R0\nEND\n").find("does not fit in 16 bits"), std::string::npos);
  load("ORG M1925\nMOV S=K-5 D=R0\nMOV S=HFFFB D=R1\nMOV S=K65535 D=R2\nMOV S=-32768 D=R3\nEND\n");
  scans(1);
  EXPECT_EQ(get("R0"), 0xFFFBu);  // -5
  EXPECT_EQ(get("R1"), 0xFFFBu);
  EXPECT_EQ(get("R2"), 0xFFFFu);
  EXPECT_EQ(get("R3"), 0x8000u);
}

TEST(ProgramRulesOfTheCell, ImdioLimits) {
  const FunctionTable fns = SoftCell::functions();
  EXPECT_EQ(errors_of("ORG M1925\nFUN 74 IMDIO D=X250 N=6\nFUN 74 IMDIO D=Y0 N=1\nEND\n", fns), "");
  EXPECT_NE(errors_of("ORG M1925\nFUN 74 IMDIO D=X250 N=7\nEND\n", fns).find("p.il:2:5: error: FUN74 IMDIO: N must be"),
            std::string::npos);
  EXPECT_NE(errors_of("ORG M1925\nFUN 74 IMDIO D=X0 N=0\nEND\n", fns).find("N must be"), std::string::npos);
  EXPECT_NE(errors_of("ORG M1925\nFUN 74 IMDIO D=M0 N=1\nEND\n", fns).find("input X or output Y"), std::string::npos);
}

// Manual II 9.5.3: the time bases are switched by the low byte of R4162, not by EN/DIS.
TEST(ProgramRulesOfTheCell, EnAndDisRefuseTimeBaseLabels) {
  const FunctionTable fns = SoftCell::functions();
  for (const char* label : {"1MSI", "2MSI", "3MSI", "4MSI", "5MSI", "10MSI", "50MSI", "100MSI"})
    for (const char* f : {"FUN 145 EN", "FUN 146 DIS"}) {
      const std::string e = errors_of(std::string("ORG M1925\n") + f + " LBL=" + label + "\nEND\n", fns);
      EXPECT_NE(e.find("p.il:2:5: error:"), std::string::npos) << f << " " << label << ": " << e;
      EXPECT_NE(e.find("R4162"), std::string::npos) << e;
    }
  EXPECT_EQ(errors_of("ORG M1925\nFUN 145 EN LBL=X0+I\nFUN 146 DIS LBL=HSC0I\nEND\n", fns), "");
}

// `plc_cell sim --set` on non-retentive addresses (M5 and S5: the default retentive
// ranges are M800-M1399 and S500-S999) holds at the first scan: it is written after RUN's
// clearing. Y0 and Y1 are driven by them in that scan.
TEST(ProgramRulesOfTheCell, SimSetHoldsOnNonRetentiveMemory) {
  const std::string prog = "/tmp/plc_cell_rules_set.il";
  std::ofstream(prog) << "ORG M5\nOUT Y0\nORG S5\nOUT Y1\nEND\n";
  const auto r = plc_cell::testing::run_tool("sim --program " + prog + " --duration 1ms --set M5=1 --set S5=1 --watch Y0,Y1");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("Y0 = 1\nY1 = 1\n"), std::string::npos) << r.out;
}
