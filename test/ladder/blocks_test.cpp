// Series, parallel and LD blocks drawn from what the IL computes.
#include "ladder_fixture.h"

namespace plc_cell {
namespace ladder {
namespace test {

TEST(LadderBlocks, SeriesContactsSitSideBySideOnOneRow) {
  const Network n = net0("ORG X0\nAND X1\nAND X2\nOUT Y0\nEND\n");
  EXPECT_TRUE(n.drawable) << n.reason;
  EXPECT_EQ(n.rows, 1);
  EXPECT_EQ(n.cols, 3);
  EXPECT_TRUE(cell(n, "X0", 0, 0));
  EXPECT_TRUE(cell(n, "X1", 0, 1));
  EXPECT_TRUE(cell(n, "X2", 0, 2));
  EXPECT_TRUE(cell(n, "Y0", 0, 3));
  EXPECT_TRUE(n.wires.empty());  // the contacts and the coil touch: no wire between them
}

TEST(LadderBlocks, OrPutsTheContactUnderTheRungBetweenTwoVerticals) {
  const Network n = net0("ORG X0\nOR X1\nOUT Y0\nEND\n");
  EXPECT_EQ(n.rows, 2);
  EXPECT_EQ(n.cols, 1);
  EXPECT_TRUE(cell(n, "X0", 0, 0));
  EXPECT_TRUE(cell(n, "X1", 1, 0));
  EXPECT_TRUE(cell(n, "Y0", 0, 1));
  EXPECT_TRUE(vwire(n, 0, 0, 1));
  EXPECT_TRUE(vwire(n, 1, 0, 1));
  EXPECT_EQ(n.wires.size(), 2u);
}

TEST(LadderBlocks, OrAfterSeriesParallelsTheWholeSeriesWithAPaddingWire) {
  // (X0 AND X1) OR X2: X2 spans the width of the series, padded by a wire.
  const Network n = net0("ORG X0\nAND X1\nOR X2\nOUT Y0\nEND\n");
  EXPECT_EQ(n.rows, 2);
  EXPECT_EQ(n.cols, 2);
  EXPECT_TRUE(cell(n, "X2", 1, 0));
  EXPECT_TRUE(hwire(n, 1, 1, 2));
  EXPECT_TRUE(vwire(n, 0, 0, 1));
  EXPECT_TRUE(vwire(n, 2, 0, 1));
  EXPECT_TRUE(cell(n, "Y0", 0, 2));
}

TEST(LadderBlocks, AndLdPutsTheBlockInSeriesAfterTheRung) {
  // X0 AND (X1 OR X2)
  const Network n = net0("ORG X0\nLD X1\nOR X2\nANDLD\nOUT Y0\nEND\n");
  EXPECT_EQ(n.rows, 2);
  EXPECT_EQ(n.cols, 2);
  EXPECT_TRUE(cell(n, "X0", 0, 0));
  EXPECT_TRUE(cell(n, "X1", 0, 1));
  EXPECT_TRUE(cell(n, "X2", 1, 1));
  EXPECT_TRUE(vwire(n, 1, 0, 1));
  EXPECT_TRUE(vwire(n, 2, 0, 1));
  EXPECT_FALSE(vwire(n, 0, 0, 1));  // X0 alone: nothing parallel to it
  EXPECT_TRUE(cell(n, "Y0", 0, 2));
}

TEST(LadderBlocks, OrLdPutsTheBlockUnderTheRung) {
  // (X0 AND X1) OR (X2 AND X3)
  const Network n = net0("ORG X0\nAND X1\nLD X2\nAND X3\nORLD\nOUT Y0\nEND\n");
  EXPECT_EQ(n.rows, 2);
  EXPECT_EQ(n.cols, 2);
  EXPECT_TRUE(cell(n, "X0", 0, 0));
  EXPECT_TRUE(cell(n, "X1", 0, 1));
  EXPECT_TRUE(cell(n, "X2", 1, 0));
  EXPECT_TRUE(cell(n, "X3", 1, 1));
  EXPECT_TRUE(vwire(n, 0, 0, 1));
  EXPECT_TRUE(vwire(n, 2, 0, 1));
  EXPECT_EQ(n.wires.size(), 2u);
}

}  // namespace test
}  // namespace ladder
}  // namespace plc_cell
