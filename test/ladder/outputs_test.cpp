// Contact forms, coils, several outputs on one network, branches, timers, counters, FUN
// boxes and flow instructions.
#include <string>

#include "ladder_fixture.h"

namespace plc_cell {
namespace ladder {
namespace test {

TEST(LadderContacts, EveryFormOfEveryContactInstruction) {
  const Layout l = lay(
      "ORG X0\nAND NOT X1\nAND TU X2\nAND TD X3\nOR X4\nOR NOT X5\nOR TU X6\nOR TD X7\n"
      "LD X8\nLD NOT X9\nANDLD\nLD TU X10\nORLD\nLD TD X11\nANDLD\nANDLD\nOUT Y0\n"
      "ORG NOT X12\nOUT Y1\nORG TU X13\nOUT Y2\nORG TD X14\nOUT Y3\nEND\n");
  const Network& n = l.networks.at(0);
  const char* forms[] = {"no", "nc", "up", "down"};
  for (int x = 0; x < 12; ++x) {
    const Element& e = at(n, "X" + std::to_string(x));
    EXPECT_EQ(e.type, "contact");
    EXPECT_EQ(e.form, forms[x % 4]) << "X" << x;
  }
  EXPECT_EQ(at(l.networks.at(1), "X12").form, "nc");
  EXPECT_EQ(at(l.networks.at(2), "X13").form, "up");
  EXPECT_EQ(at(l.networks.at(3), "X14").form, "down");
}

TEST(LadderOutputs, CoilsOfOneResultStackAtTheRightOneARow) {
  const Network n = net0("ORG X0\nOUT Y0\nOUT NOT Y1\nSET Y2\nRST Y3\nRST R5\nRST DR6\nEND\n");
  EXPECT_TRUE(n.drawable) << n.reason;
  EXPECT_EQ(n.rows, 6);
  EXPECT_EQ(n.cols, 1);
  const char* addr[] = {"Y0", "Y1", "Y2", "Y3", "R5", "DR6"};
  const char* form[] = {"out", "out_not", "set", "rst", "rst", "rst"};
  for (int k = 0; k < 6; ++k) {
    EXPECT_TRUE(cell(n, addr[k], k, 1));
    EXPECT_EQ(at(n, addr[k]).type, "coil");
    EXPECT_EQ(at(n, addr[k]).form, form[k]);
  }
  EXPECT_TRUE(vwire(n, 1, 0, 5));  // the rung's exit feeds all six
}

TEST(LadderOutputs, ContactsBetweenOutputsBranchOffTheRungAbove) {
  // Y0 = X0, Y1 = X0 AND X1, Y2 = X0 AND X1 AND X2: each branch hangs off the one above.
  const Network n = net0("ORG X0\nOUT Y0\nAND X1\nOUT Y1\nAND NOT X2\nOUT Y2\nEND\n");
  EXPECT_TRUE(n.drawable) << n.reason;
  EXPECT_EQ(n.rows, 3);
  EXPECT_EQ(n.cols, 3);
  EXPECT_TRUE(cell(n, "X0", 0, 0));
  EXPECT_TRUE(cell(n, "Y0", 0, 3));
  EXPECT_TRUE(hwire(n, 0, 1, 3));
  EXPECT_TRUE(vwire(n, 1, 0, 1));
  EXPECT_TRUE(cell(n, "X1", 1, 1));
  EXPECT_TRUE(cell(n, "Y1", 1, 3));
  EXPECT_TRUE(hwire(n, 1, 2, 3));
  EXPECT_TRUE(vwire(n, 2, 1, 2));
  EXPECT_TRUE(cell(n, "X2", 2, 2));
  EXPECT_TRUE(cell(n, "Y2", 2, 3));
}

TEST(LadderOutputs, ABlockAndedAfterAnOutputIsABranch) {
  // Y0 = X0; Y1 = X0 AND (X1 OR X2); Y2 too.
  const Network n = net0("ORG X0\nOUT Y0\nLD X1\nOR X2\nANDLD\nOUT Y1\nOUT Y2\nEND\n");
  EXPECT_TRUE(n.drawable) << n.reason;
  EXPECT_EQ(n.rows, 3);
  EXPECT_EQ(n.cols, 2);
  EXPECT_TRUE(cell(n, "Y0", 0, 2));
  EXPECT_TRUE(cell(n, "X1", 1, 1));
  EXPECT_TRUE(cell(n, "X2", 2, 1));
  EXPECT_TRUE(cell(n, "Y1", 1, 2));
  EXPECT_TRUE(cell(n, "Y2", 2, 2));
  EXPECT_TRUE(vwire(n, 2, 1, 2));  // X1 OR X2's right side, and Y1/Y2 sharing it
}

TEST(LadderOutputs, AnOrAfterAnOutputHasNoPlanarLadder) {
  // Y1 = X0 OR X1, but X1 joined at Y0's branch point would drive Y0 too.
  const Layout l = lay("ORG X0\nOUT Y0\nOR X1\nOUT Y1\nORG X2\nOUT Y2\nEND\n");
  const Network& n = l.networks.at(0);
  EXPECT_FALSE(n.drawable);
  EXPECT_NE(n.reason.find("line 4"), std::string::npos) << n.reason;
  EXPECT_NE(n.reason.find("OR"), std::string::npos) << n.reason;
  EXPECT_TRUE(n.elements.empty());
  ASSERT_EQ(n.il.size(), 4u);  // the page shows the IL instead
  EXPECT_EQ(n.il[2].text, "OR X1");
  EXPECT_TRUE(l.networks.at(1).drawable);  // the next network is not affected
}

TEST(LadderOutputs, AnOrLdAfterAnOutputHasNoPlanarLadder) {
  const Network n = net0("ORG X0\nOUT Y0\nLD X1\nORLD\nOUT Y1\nEND\n");
  EXPECT_FALSE(n.drawable);
  EXPECT_NE(n.reason.find("line 5"), std::string::npos) << n.reason;
}

TEST(LadderOutputs, ABlockLeftOpenIsNotDrawable) {
  const Layout l = lay("ORG X0\nLD X1\nORG X2\nOUT Y0\nEND\n");
  EXPECT_FALSE(l.networks.at(0).drawable);
  EXPECT_NE(l.networks.at(0).reason.find("left open"), std::string::npos) << l.networks.at(0).reason;
  EXPECT_TRUE(l.networks.at(1).drawable);
}

TEST(LadderOutputs, ContactsAfterTheLastOutputHangBelowIt) {
  const Network n = net0("ORG X0\nOUT Y0\nAND X1\nORG X2\nOUT Y1\nEND\n");
  EXPECT_TRUE(n.drawable) << n.reason;
  EXPECT_TRUE(cell(n, "X1", 1, 1));
  EXPECT_TRUE(vwire(n, 1, 0, 1));
  EXPECT_EQ(n.cols, 2);
  EXPECT_TRUE(cell(n, "Y0", 0, 2));
}

TEST(LadderOutputs, AnOutputAfterACallIsNotDrawable) {
  // After a CALL that ran, the result is whatever the subroutine left.
  const Layout l = lay("ORG X0\nCALL SUB\nOUT Y0\nEND\nLBL SUB\nORG X1\nOUT Y1\nRTS\n");
  EXPECT_FALSE(l.networks.at(0).drawable);
  EXPECT_NE(l.networks.at(0).reason.find("CALL"), std::string::npos) << l.networks.at(0).reason;
}

TEST(LadderOutputs, TimersAndCountersShowPresetAndValueAddresses) {
  const Layout l = lay("ORG X0\nTMR T50 15\nTMR T1 R2\nORG X1\nCTR C0 9999\nORG X2\nCTR C200 R10\nEND\n",
                       {{"pick_time", parse_address("T50")}});
  const Network& t = l.networks.at(0);
  const Element& t50 = at(t, "T50");
  EXPECT_EQ(t50.type, "timer");
  EXPECT_EQ(t50.name, "pick_time");
  EXPECT_EQ(t50.preset, "15");
  EXPECT_EQ(t50.values, (std::vector<std::string>{"T50", "RT50"}));
  EXPECT_TRUE(cell(t, "T50", 0, 1));
  EXPECT_TRUE(cell(t, "T1", 1, 1));
  EXPECT_EQ(at(t, "T1").preset_address, "R2");
  const Element& c0 = at(l.networks.at(1), "C0");
  EXPECT_EQ(c0.type, "counter");
  EXPECT_EQ(c0.preset, "9999");
  EXPECT_EQ(c0.values, (std::vector<std::string>{"C0", "RC0"}));
  const Element& c200 = at(l.networks.at(2), "C200");
  EXPECT_EQ(c200.values, (std::vector<std::string>{"C200", "DRC200"}));  // a 32-bit counter
  EXPECT_EQ(c200.preset_address, "DR10");                                  // R10 and R11
}

TEST(LadderOutputs, FunBoxesShowTheirOperandsWithNamesAndAddresses) {
  const Layout l = lay("ORG X0\nFUN 11 Sa=D0 Sb=K1 D=D2\nMOV.DP S=R0 D=DR4\nEND\n",
                       {{"speed", parse_address("D0")}});
  const Network& n = l.networks.at(0);
  ASSERT_EQ(n.elements.size(), 3u);
  const Element& add = n.elements[1];
  EXPECT_EQ(add.type, "fun");
  EXPECT_EQ(add.fun, 11);
  EXPECT_EQ(add.mnemonic, "ADD");
  EXPECT_FALSE(add.pulse);
  EXPECT_FALSE(add.d32);
  EXPECT_EQ(add.row, 0);
  EXPECT_EQ(add.col, 1);
  ASSERT_EQ(add.operands.size(), 3u);  // the optional flags were not given
  EXPECT_EQ(add.operands[0].name, "Sa");
  EXPECT_EQ(add.operands[0].address, "D0");
  EXPECT_EQ(add.operands[0].signal, "speed");
  EXPECT_EQ(add.operands[1].text, "K1");
  EXPECT_EQ(add.operands[1].address, "");
  const Element& mov = n.elements[2];
  EXPECT_EQ(mov.mnemonic, "MOV");
  EXPECT_TRUE(mov.pulse);
  EXPECT_TRUE(mov.d32);
  EXPECT_EQ(mov.row, 1);
  EXPECT_EQ(mov.operands[0].address, "DR0");  // .D: R0 is the pair R0, R1
  EXPECT_EQ(mov.inputs.size(), 1u);
}

TEST(LadderOutputs, AFunWithoutAFunctionTableIsFunN) {
  const std::string il = "ORG X0\nFUN 11 Sa=D0 Sb=K1 D=D2\nEND\n";
  const Program p = parse_program(il, "t.il", functions());
  const Layout l = layout(p, il);
  EXPECT_EQ(l.networks.at(0).elements.at(1).mnemonic, "FUN 11");
}

TEST(LadderOutputs, AFunWithSeveralInputsTakesARowPerInput) {
  FunctionTable fns = FunctionTable::with_core_functions();
  FunctionSpec s;
  s.number = 900;
  s.mnemonic = "TRIO";
  s.inputs = {"EN", "PAU", "ABT"};
  s.handler = [](ExecContext&, const BoundOperand*) {};
  fns.add(s);
  const std::string il = "ORG X0\nLD X1\nAND X2\nLD X3\nTRIO\nEND\n";
  const Program p = parse_program(il, "t.il", fns);
  const Network n = layout(p, il, {}, &fns).networks.at(0);
  EXPECT_TRUE(n.drawable) << n.reason;
  EXPECT_EQ(n.rows, 3);
  EXPECT_EQ(n.cols, 2);
  EXPECT_TRUE(cell(n, "X0", 0, 0));
  EXPECT_TRUE(cell(n, "X1", 1, 0));
  EXPECT_TRUE(cell(n, "X2", 1, 1));
  EXPECT_TRUE(cell(n, "X3", 2, 0));
  EXPECT_TRUE(hwire(n, 0, 1, 2));
  EXPECT_TRUE(hwire(n, 2, 1, 2));
  const Element& f = n.elements.back();
  EXPECT_EQ(f.type, "fun");
  EXPECT_EQ(f.row, 0);
  EXPECT_EQ(f.col, 2);
  ASSERT_EQ(f.inputs.size(), 3u);
  EXPECT_EQ(f.inputs[1].name, "PAU");
  EXPECT_EQ(f.inputs[1].row, 1);
  EXPECT_EQ(f.inputs[2].name, "ABT");
  EXPECT_EQ(f.inputs[2].row, 2);

  const std::string after = "ORG X0\nLD X1\nLD X2\nTRIO\nOUT Y0\nEND\n";
  const Network m = layout(parse_program(after, "t.il", fns), after, {}, &fns).networks.at(0);
  EXPECT_FALSE(m.drawable);
  EXPECT_NE(m.reason.find("line 5"), std::string::npos) << m.reason;
}

TEST(LadderFlow, JumpsCallsLabelsAndLoopsAreBoxes) {
  const Layout l = lay(
      "ORG X0\nJMP SKIP\nORG X1\nOUT Y0\nLBL SKIP\nORG X2\nCALL SUB\nFOR 3\nORG X3\nOUT Y1\nNEXT\nEND\n"
      "LBL SUB\nORG X4\nOUT Y2\nRTS\n");
  const auto& nets = l.networks;
  ASSERT_EQ(nets.size(), 11u);
  const Element& jmp = nets[0].elements.at(1);
  EXPECT_EQ(jmp.type, "jump");
  EXPECT_EQ(jmp.label, "SKIP");
  EXPECT_EQ(jmp.col, nets[0].cols);
  EXPECT_EQ(nets[2].elements.at(0).type, "label");
  EXPECT_EQ(nets[2].elements.at(0).label, "SKIP");
  EXPECT_EQ(nets[3].elements.at(1).type, "call");
  const Element& loop = nets[4].elements.at(0);
  EXPECT_EQ(loop.type, "flow");
  EXPECT_EQ(loop.form, "FOR");
  ASSERT_EQ(loop.operands.size(), 1u);
  EXPECT_EQ(loop.operands[0].text, "K3");
  EXPECT_EQ(nets[6].elements.at(0).form, "NEXT");
  EXPECT_EQ(nets[7].elements.at(0).form, "END");
  EXPECT_EQ(nets[8].elements.at(0).label, "SUB");
  EXPECT_EQ(nets[10].elements.at(0).form, "RTS");
  for (const Network& n : nets) EXPECT_TRUE(n.drawable) << n.index << ": " << n.reason;
}

TEST(LadderFlow, AnInterruptRoutineEndsWithAnRtiBox) {
  const Layout l = lay("ORG X0\nOUT Y0\nEND\nLBL 1MSI\nORG M0\nOUT Y1\nRTI\n");
  ASSERT_EQ(l.networks.size(), 5u);
  EXPECT_EQ(l.networks[2].elements.at(0).type, "label");
  EXPECT_EQ(l.networks[2].elements.at(0).label, "1MSI");
  EXPECT_EQ(l.networks[4].elements.at(0).type, "flow");
  EXPECT_EQ(l.networks[4].elements.at(0).form, "RTI");
  EXPECT_EQ(l.networks[4].rows, 1);
  EXPECT_EQ(l.networks[4].cols, 0);
}

}  // namespace test
}  // namespace ladder
}  // namespace plc_cell
