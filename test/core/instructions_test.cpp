// Every IL instruction against values worked out by hand.
#include "plc_fixture.h"

using namespace plc_cell;

class Instructions : public BothEnginesFixture {};
PLC_CELL_ON_BOTH_ENGINES(Instructions);

TEST_P(Instructions, ContactsAndCoils) {
  load("ORG X0\nAND X1\nOUT Y0\n"
       "ORG X0\nOR X1\nOUT Y1\n"
       "ORG NOT X0\nAND NOT X1\nOUT Y2\n"
       "ORG X0\nOR NOT X1\nOUT NOT Y3\n"
       "END\n");
  const int table[4][2] = {{0, 0}, {0, 1}, {1, 0}, {1, 1}};
  for (const auto& row : table) {
    const bool a = row[0], b = row[1];
    input(0, a);
    input(1, b);
    scans(1);
    EXPECT_EQ(get("Y0"), uint32_t(a && b));
    EXPECT_EQ(get("Y1"), uint32_t(a || b));
    EXPECT_EQ(get("Y2"), uint32_t(!a && !b));
    EXPECT_EQ(get("Y3"), uint32_t(!(a || !b)));
  }
}

TEST_P(Instructions, BlocksWithAndLdOrLd) {
  // Y0 = (X0 OR X1) AND (X2 OR X3);  Y1 = (X0 AND X1) OR (X2 AND X3)
  load("ORG X0\nOR X1\nLD X2\nOR X3\nANDLD\nOUT Y0\n"
       "ORG X0\nAND X1\nLD X2\nAND X3\nORLD\nOUT Y1\n"
       "END\n");
  for (int v = 0; v < 16; ++v) {
    for (int k = 0; k < 4; ++k) input(k, (v >> k) & 1);
    scans(1);
    const bool x0 = v & 1, x1 = v & 2, x2 = v & 4, x3 = v & 8;
    EXPECT_EQ(get("Y0"), uint32_t((x0 || x1) && (x2 || x3))) << v;
    EXPECT_EQ(get("Y1"), uint32_t((x0 && x1) || (x2 && x3))) << v;
  }
}

TEST_P(Instructions, EdgeContactsPulseForOneScan) {
  load("ORG TU X0\nOUT Y0\nORG TD X0\nOUT Y1\nORG X1\nAND TU X0\nOUT Y2\nEND\n");
  scans(1);
  EXPECT_EQ(get("Y0"), 0u);
  input(0, true);
  scans(1);
  EXPECT_EQ(get("Y0"), 1u);
  EXPECT_EQ(get("Y1"), 0u);
  EXPECT_EQ(get("Y2"), 0u);  // X1 was off on the rising edge
  scans(1);
  EXPECT_EQ(get("Y0"), 0u);
  input(0, false);
  scans(1);
  EXPECT_EQ(get("Y1"), 1u);
  scans(1);
  EXPECT_EQ(get("Y1"), 0u);
  input(1, true);
  input(0, true);
  scans(1);
  EXPECT_EQ(get("Y2"), 1u);
}

TEST_P(Instructions, SetResetLatch) {
  load("ORG X0\nSET Y0\nORG X1\nRST Y0\nEND\n");
  input(0, true);
  scans(1);
  input(0, false);
  scans(3);
  EXPECT_EQ(get("Y0"), 1u);
  input(1, true);
  scans(1);
  EXPECT_EQ(get("Y0"), 0u);
  input(0, true);  // both on: RST comes later in the scan and wins
  scans(1);
  EXPECT_EQ(get("Y0"), 0u);
}

TEST_P(Instructions, MultipleOutputsShareOneNetwork) {
  load("ORG X0\nOUT Y0\nOUT M5\nOUT NOT Y1\nEND\n");
  input(0, true);
  scans(1);
  EXPECT_EQ(get("Y0"), 1u);
  EXPECT_EQ(get("M5"), 1u);
  EXPECT_EQ(get("Y1"), 0u);
}

TEST_P(Instructions, MoveAndWordViews) {
  load("ORG M1925\nFUN 8 S=1234 D=R0\nMOV R0 D5\nFUN 8 S=HAAAA D=WY8\nFUN 8 S=WX0 D=R1\n"
       "MOV.D S=H12345678 D=DR10\nMOVN S=0 D=R2\nEND\n");
  input(0, true);
  input(15, true);
  scans(1);
  EXPECT_EQ(get("R0"), 1234u);
  EXPECT_EQ(get("D5"), 1234u);
  EXPECT_EQ(get("WY8"), 0xAAAAu);
  EXPECT_EQ(get("Y9"), 1u);
  EXPECT_EQ(get("Y8"), 0u);
  EXPECT_EQ(get("R1"), 0x8001u);
  EXPECT_EQ(get("R10"), 0x5678u);
  EXPECT_EQ(get("R11"), 0x1234u);
  EXPECT_EQ(get("R2"), 0xFFFFu);
}

TEST_P(Instructions, InstructionsRunOnlyWhenEnabled) {
  load("ORG X0\nMOV S=7 D=R0\nORG X1\nINC R1\nEND\n");
  scans(5);
  EXPECT_EQ(get("R0"), 0u);
  EXPECT_EQ(get("R1"), 0u);
  input(1, true);
  scans(5);
  EXPECT_EQ(get("R1"), 5u);  // INC without P runs every scan
}

TEST_P(Instructions, PulseFormRunsOnTheRisingEdgeOnly) {
  load("ORG X1\nINC.P R1\nORG X1\nFUN 15P D=R2\nEND\n");
  input(1, true);
  scans(5);
  EXPECT_EQ(get("R1"), 1u);
  EXPECT_EQ(get("R2"), 1u);
  input(1, false);
  scans(1);
  input(1, true);
  scans(3);
  EXPECT_EQ(get("R1"), 2u);
}

TEST_P(Instructions, AddSubWithSignedFlags) {
  load("ORG M1925\n"
       "ADD Sa=R0 Sb=R1 D=R2 ZR=M0 CY=M1 BR=M2\n"
       "SUB Sa=R0 Sb=R1 D=R3 ZR=M3 CY=M4 BR=M5\n"
       "ADD.D Sa=DR10 Sb=DR12 D=DR14\n"
       "END\n");
  put("R0", 30000);
  put("R1", 5000);
  put("DR10", 100000);
  put("DR12", 0xFFFFFFFF);  // -1
  scans(1);
  EXPECT_EQ(sget("R2"), int16_t(35000 - 65536));  // wrapped
  EXPECT_EQ(get("M1"), 1u);                       // carry: above +32767
  EXPECT_EQ(get("M0"), 0u);
  EXPECT_EQ(sget("R3"), 25000);
  EXPECT_EQ(get("M4"), 0u);
  EXPECT_EQ(plc.read(parse_address("DR14"), 1)[0], 99999u);
  put("R0", uint16_t(-30000));
  put("R1", 5000);
  scans(1);
  EXPECT_EQ(get("M5"), 1u);  // borrow: below -32768
  put("R0", 5);
  put("R1", 5);
  scans(1);
  EXPECT_EQ(get("M3"), 1u);  // 5 - 5 = 0
  EXPECT_EQ(sget("R2"), 10);
}

TEST_P(Instructions, MultiplyAndDivide) {
  load("ORG M1925\n"
       "MUL Sa=R0 Sb=R1 D=R10\n"
       "DIV Sa=R0 Sb=R1 D=R20 ERR=M0\n"
       "DIV Sa=R0 Sb=R2 D=R22 ERR=M1\n"
       "MUL.D Sa=DR30 Sb=DR32 D=DR40\n"
       "DIV.D Sa=DR30 Sb=DR32 D=DR50\n"
       "END\n");
  put("R0", uint16_t(-1000));
  put("R1", 300);
  put("R2", 0);
  put("R22", 77);
  put("DR30", 100000);
  put("DR32", 70000);
  scans(1);
  EXPECT_EQ(plc.read(parse_address("DR10"), 1)[0], uint32_t(-300000));
  EXPECT_EQ(sget("R20"), -3);   // quotient
  EXPECT_EQ(sget("R21"), -100); // remainder
  EXPECT_EQ(get("M0"), 0u);
  EXPECT_EQ(get("M1"), 1u);     // divide by zero
  EXPECT_EQ(get("R22"), 77u);   // untouched
  // 100000 * 70000 = 7,000,000,000 = 0x1_A13B_8600 over four words
  EXPECT_EQ(plc.read(parse_address("DR40"), 1)[0], 0xA13B8600u);
  EXPECT_EQ(plc.read(parse_address("DR42"), 1)[0], 0x1u);
  EXPECT_EQ(plc.read(parse_address("DR50"), 1)[0], 1u);
  EXPECT_EQ(plc.read(parse_address("DR52"), 1)[0], 30000u);
}

TEST_P(Instructions, IncDecWrap) {
  load("ORG M1925\nINC D=R0 OVF=M0\nDEC D=R1 UDF=M1\nEND\n");
  put("R0", 32767);
  put("R1", uint16_t(-32768));
  scans(1);
  EXPECT_EQ(sget("R0"), -32768);
  EXPECT_EQ(get("M0"), 1u);
  EXPECT_EQ(sget("R1"), 32767);
  EXPECT_EQ(get("M1"), 1u);
}

TEST_P(Instructions, CompareIsSigned) {
  load("ORG M1925\nCMP Sa=R0 Sb=R1 EQ=M0 GT=M1 LT=M2\nCMP.D Sa=DR10 Sb=100000 EQ=M3 GT=M4 LT=M5\nEND\n");
  put("R0", uint16_t(-1));
  put("R1", 1);
  put("DR10", 100000);
  scans(1);
  EXPECT_EQ(get("M0"), 0u);
  EXPECT_EQ(get("M1"), 0u);
  EXPECT_EQ(get("M2"), 1u);
  EXPECT_EQ(get("M3"), 1u);
  EXPECT_EQ(get("M4") + get("M5"), 0u);
}

TEST_P(Instructions, LogicAndShift) {
  load("ORG M1925\nWAND Sa=R0 Sb=HFF00 D=R1\nFUN 19 Sa=R0 Sb=H000F D=R2\nWXOR Sa=R0 Sb=HFFFF D=R3 ZR=M0\n"
       "MOV R0 R4\nSHL D=R4 N=4 OTB=M1\nMOV R0 R5\nSHR D=R5 N=1 OTB=M2\nEND\n");
  put("R0", 0x1234);
  scans(1);
  EXPECT_EQ(get("R1"), 0x1200u);
  EXPECT_EQ(get("R2"), 0x123Fu);
  EXPECT_EQ(get("R3"), 0xEDCBu);
  EXPECT_EQ(get("M0"), 0u);
  EXPECT_EQ(get("R4"), 0x2340u);
  EXPECT_EQ(get("M1"), 1u);  // the last bit shifted out of 0x1234 << 4 is bit 12 = 1
  EXPECT_EQ(get("R5"), 0x091Au);
  EXPECT_EQ(get("M2"), 0u);
}

TEST_P(Instructions, BcdConversions) {
  load("ORG M1925\nBCD S=R0 D=R1 ERR=M0\nBIN S=R2 D=R3 ERR=M1\nBCD.D S=DR10 D=DR12\nBIN S=R4 D=R5 ERR=M2\nEND\n");
  put("R0", 1234);
  put("R2", 0x9876);
  put("DR10", 12345678);
  put("R4", 0x12A4);  // A is no BCD digit
  put("R5", 55);
  scans(1);
  EXPECT_EQ(get("R1"), 0x1234u);
  EXPECT_EQ(get("R3"), 9876u);
  EXPECT_EQ(plc.read(parse_address("DR12"), 1)[0], 0x12345678u);
  EXPECT_EQ(get("M0") + get("M1"), 0u);
  EXPECT_EQ(get("M2"), 1u);
  EXPECT_EQ(get("R5"), 55u);
  put("R0", 10000);  // out of range for 4 digits
  scans(1);
  EXPECT_EQ(get("M0"), 1u);
  EXPECT_EQ(get("R1"), 0x1234u);
}

TEST_P(Instructions, JumpSkipsCode) {
  load("ORG X0\nJMP skip\nORG M1925\nINC R0\nLBL skip\nORG M1925\nINC R1\nEND\n");
  scans(3);
  input(0, true);
  scans(2);
  EXPECT_EQ(get("R0"), 3u);
  EXPECT_EQ(get("R1"), 5u);
}

TEST_P(Instructions, CallAndReturn) {
  load("ORG X0\nCALL add_ten\nORG M1925\nINC R1\nEND\n"
       "LBL add_ten\nORG M1925\nADD Sa=R0 Sb=10 D=R0\nRTS\n");
  scans(2);
  input(0, true);
  scans(3);
  EXPECT_EQ(get("R0"), 30u);
  EXPECT_EQ(get("R1"), 5u);
}

TEST_P(Instructions, ForNextLoops) {
  // The manual's CLINK example loops over a table with FOR/NEXT.
  load("ORG M1925\nMOV S=0 D=R0\nFOR 10\nORG M1925\nINC R0\nNEXT\nFOR R5\nORG M1925\nINC R1\nNEXT\nEND\n");
  put("R5", 3);
  scans(2);
  EXPECT_EQ(get("R0"), 10u);
  EXPECT_EQ(get("R1"), 6u);
  put("R5", 0);  // zero iterations skips the body
  scans(1);
  EXPECT_EQ(get("R1"), 6u);
}

TEST_P(Instructions, RunawayLoopTripsTheWatchdogAndStops) {
  load("LBL top\nORG M1925\nJMP top\nEND\n");
  plc.locked([](ScanEngine& e, Memory&) {
    e.interpreter().set_loop_budget(1000);
    return 0;
  });
  scans(1);
  EXPECT_EQ(plc.mode(), RunMode::Stop);
  const std::string fault = plc.locked([](ScanEngine& e, Memory&) { return e.fault(); });
  EXPECT_NE(fault.find("test.il:3: watchdog"), std::string::npos) << fault;
}

TEST_P(Instructions, RecursionBeyondTheCallDepthFaults) {
  load("ORG M1925\nCALL r\nEND\nLBL r\nORG M1925\nCALL r\nRTS\n");
  scans(1);
  EXPECT_EQ(plc.mode(), RunMode::Stop);
  const std::string fault = plc.locked([](ScanEngine& e, Memory&) { return e.fault(); });
  EXPECT_NE(fault.find("nested deeper than 16"), std::string::npos) << fault;
}
