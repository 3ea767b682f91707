// Power flow worked out by hand from the values of one or two frames.
#include <algorithm>
#include <string>

#include "ladder_fixture.h"
#include "plc_cell/ladder/flow.h"

namespace plc_cell {
namespace ladder {
namespace test {

namespace {

Values frame(std::initializer_list<std::pair<const char*, uint32_t>> values) {
  Values v;
  for (const auto& kv : values) v.set(parse_address(kv.first), kv.second);
  return v;
}

bool on(const Flow& f, int id) { return std::find(f.on.begin(), f.on.end(), id) != f.on.end(); }

int vwire_id(const Network& n, int col, int from, int to) {
  for (const Wire& w : n.wires)
    if (w.vertical && w.col == col && w.from == from && w.to == to) return w.id;
  ADD_FAILURE() << "no vertical wire at " << col;
  return -1;
}

int hwire_id(const Network& n, int row, int from, int to) {
  for (const Wire& w : n.wires)
    if (!w.vertical && w.row == row && w.from == from && w.to == to) return w.id;
  ADD_FAILURE() << "no horizontal wire on row " << row;
  return -1;
}

}  // namespace

TEST(LadderPowerFlow, TheLatchPassesPowerThroughWhatIsClosed) {
  // (X0 OR Y0) AND X1 -> Y0
  const Network n = net0("ORG X0\nOR Y0\nAND X1\nOUT Y0\nEND\n");
  const int x0 = at(n, "X0").id, y0c = at(n, "Y0", "contact").id, x1 = at(n, "X1").id;
  const int coil = at(n, "Y0", "coil").id;
  const int left = vwire_id(n, 0, 0, 1), right = vwire_id(n, 1, 0, 1);
  const Values start = frame({{"X0", 1}, {"X1", 1}});
  Flow f = flow(n, start.lookup(), start.lookup());
  EXPECT_EQ(f.net, 0);
  EXPECT_TRUE(on(f, x0) && on(f, x1) && on(f, coil) && on(f, left) && on(f, right));
  EXPECT_FALSE(on(f, y0c));  // Y0 is still 0 in this frame: its contact is open

  const Values stopped = frame({{"X0", 1}, {"X1", 0}, {"Y0", 1}});
  f = flow(n, stopped.lookup(), stopped.lookup());
  EXPECT_TRUE(on(f, x0) && on(f, y0c) && on(f, right));
  EXPECT_FALSE(on(f, x1));
  EXPECT_FALSE(on(f, coil));

  const Values idle = frame({{"X1", 1}});
  f = flow(n, idle.lookup(), idle.lookup());
  EXPECT_TRUE(on(f, left));  // the left rail's vertical is always powered
  EXPECT_FALSE(on(f, right) || on(f, x1) || on(f, coil) || on(f, x0));
}

TEST(LadderPowerFlow, NotContactsConductWhenTheirBitIsOff) {
  const Network n = net0("ORG NOT X0\nOUT Y0\nEND\n");
  const Values off = frame({}), set = frame({{"X0", 1}});
  EXPECT_TRUE(on(flow(n, off.lookup(), off.lookup()), at(n, "Y0").id));
  EXPECT_FALSE(on(flow(n, set.lookup(), set.lookup()), at(n, "Y0").id));
}

TEST(LadderPowerFlow, EdgeContactsCompareTheTwoFrames) {
  const Layout l = lay("ORG TU X0\nOUT Y0\nORG TD X0\nOUT Y1\nEND\n");
  const Network& up = l.networks.at(0);
  const Network& down = l.networks.at(1);
  const Values lo = frame({}), hi = frame({{"X0", 1}});
  const int y0 = at(up, "Y0").id, y1 = at(down, "Y1").id;
  EXPECT_TRUE(on(flow(up, hi.lookup(), lo.lookup()), y0));   // rose
  EXPECT_FALSE(on(flow(up, hi.lookup(), hi.lookup()), y0));  // stays on
  EXPECT_FALSE(on(flow(up, lo.lookup(), hi.lookup()), y0));  // fell
  EXPECT_TRUE(on(flow(down, lo.lookup(), hi.lookup()), y1));
  EXPECT_FALSE(on(flow(down, lo.lookup(), lo.lookup()), y1));
  EXPECT_FALSE(on(flow(down, hi.lookup(), lo.lookup()), y1));
}

TEST(LadderPowerFlow, ABranchIsPoweredFromTheRungAbove) {
  // Y0 = X0; Y1 = X0 AND X1
  const Network n = net0("ORG X0\nOUT Y0\nAND X1\nOUT Y1\nEND\n");
  const Values v = frame({{"X0", 1}});
  const Flow f = flow(n, v.lookup(), v.lookup());
  EXPECT_TRUE(on(f, at(n, "Y0").id));
  EXPECT_TRUE(on(f, hwire_id(n, 0, 1, 2)));
  EXPECT_TRUE(on(f, vwire_id(n, 1, 0, 1)));
  EXPECT_FALSE(on(f, at(n, "X1").id));
  EXPECT_FALSE(on(f, at(n, "Y1").id));
  const Values none = frame({{"X1", 1}});
  const Flow g = flow(n, none.lookup(), none.lookup());
  EXPECT_FALSE(on(g, at(n, "X1").id));  // closed, but nothing feeds it
  EXPECT_FALSE(on(g, vwire_id(n, 1, 0, 1)));
}

TEST(LadderPowerFlow, AFunWithSeveralInputsIsOnWithItsEnInput) {
  FunctionTable fns = FunctionTable::with_core_functions();
  FunctionSpec s;
  s.number = 900;
  s.mnemonic = "DUO";
  s.inputs = {"EN", "CLR"};
  s.handler = [](ExecContext&, const BoundOperand*) {};
  fns.add(s);
  const std::string il = "ORG X0\nLD X1\nDUO\nEND\n";
  const Network n = layout(parse_program(il, "t.il", fns), il, {}, &fns).networks.at(0);
  const Values clr = frame({{"X1", 1}}), en = frame({{"X0", 1}});
  EXPECT_FALSE(on(flow(n, clr.lookup(), clr.lookup()), n.elements.back().id));
  EXPECT_TRUE(on(flow(n, clr.lookup(), clr.lookup()), at(n, "X1").id));
  EXPECT_TRUE(on(flow(n, en.lookup(), en.lookup()), n.elements.back().id));
}

TEST(LadderAddresses, EverythingTheNetworkShowsOnce) {
  const Layout l = lay("ORG X0\nAND NOT X0\nOUT Y0\nTMR T5 R7\nCTR C201 9\nFUN 11 Sa=D0 Sb=K1 D=D2\nEND\n");
  std::vector<std::string> got;
  for (const Address& a : addresses(l.networks.at(0))) got.push_back(format_address(a));
  EXPECT_EQ(got, (std::vector<std::string>{"X0", "Y0", "T5", "RT5", "R7", "C201", "DRC201", "D0", "D2"}));
  EXPECT_TRUE(addresses(l.networks.at(1)).empty());  // END
}

}  // namespace test
}  // namespace ladder
}  // namespace plc_cell
