// Series, parallel and LD blocks drawn from what the IL computes.
#include <set>
#include <string>
#include <utility>

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


TEST(LadderBlocks, AParallelBlockInsideAnAndLdBlock) {
  // X0 AND ((X1 AND (X2 OR X3)) OR X4): depth 2.
  const Network n = net0("ORG X0\nLD X1\nLD X2\nOR X3\nANDLD\nOR X4\nANDLD\nOUT Y0\nEND\n");
  EXPECT_TRUE(n.drawable) << n.reason;
  EXPECT_EQ(n.rows, 3);
  EXPECT_EQ(n.cols, 3);
  EXPECT_TRUE(cell(n, "X0", 0, 0));
  EXPECT_TRUE(cell(n, "X1", 0, 1));
  EXPECT_TRUE(cell(n, "X2", 0, 2));
  EXPECT_TRUE(cell(n, "X3", 1, 2));
  EXPECT_TRUE(vwire(n, 2, 0, 1));  // X2 OR X3
  EXPECT_TRUE(vwire(n, 3, 0, 1));
  EXPECT_TRUE(cell(n, "X4", 2, 1));  // under the two rows of X1 AND (X2 OR X3)
  EXPECT_TRUE(hwire(n, 2, 2, 3));
  EXPECT_TRUE(vwire(n, 1, 0, 2));  // (...) OR X4
  EXPECT_TRUE(vwire(n, 3, 0, 2));
  EXPECT_TRUE(cell(n, "Y0", 0, 3));
}

TEST(LadderBlocks, ThreeBlocksDeep) {
  // X0 AND (X1 OR (X2 AND (X3 OR X4))): the LD X1 block waits under two more.
  const Network n = net0("ORG X0\nLD X1\nLD X2\nLD X3\nOR X4\nANDLD\nORLD\nANDLD\nOUT Y0\nEND\n");
  EXPECT_TRUE(n.drawable) << n.reason;
  EXPECT_EQ(n.rows, 3);
  EXPECT_EQ(n.cols, 3);
  EXPECT_TRUE(cell(n, "X0", 0, 0));
  EXPECT_TRUE(cell(n, "X1", 0, 1));
  EXPECT_TRUE(hwire(n, 0, 2, 3));  // X1 padded to the width of X2 AND (...)
  EXPECT_TRUE(cell(n, "X2", 1, 1));
  EXPECT_TRUE(cell(n, "X3", 1, 2));
  EXPECT_TRUE(cell(n, "X4", 2, 2));
  EXPECT_TRUE(vwire(n, 2, 1, 2));  // X3 OR X4
  EXPECT_TRUE(vwire(n, 3, 1, 2));
  EXPECT_TRUE(vwire(n, 1, 0, 1));  // X1 OR (...)
  EXPECT_TRUE(vwire(n, 3, 0, 1));
  EXPECT_TRUE(cell(n, "Y0", 0, 3));
}

TEST(LadderBlocks, OrLdOfAnOrLdIsOneParallelOfThree) {
  // X0 OR (X1 OR (X2 AND X3)): OR is associative, so three branches between two verticals.
  const Network n = net0("ORG X0\nLD X1\nLD X2\nAND X3\nORLD\nORLD\nOUT Y0\nEND\n");
  EXPECT_EQ(n.rows, 3);
  EXPECT_EQ(n.cols, 2);
  EXPECT_TRUE(cell(n, "X0", 0, 0));
  EXPECT_TRUE(cell(n, "X1", 1, 0));
  EXPECT_TRUE(cell(n, "X2", 2, 0));
  EXPECT_TRUE(cell(n, "X3", 2, 1));
  EXPECT_TRUE(hwire(n, 0, 1, 2));
  EXPECT_TRUE(hwire(n, 1, 1, 2));
  EXPECT_TRUE(vwire(n, 0, 0, 2));
  EXPECT_TRUE(vwire(n, 2, 0, 2));
  EXPECT_EQ(n.wires.size(), 4u);
}

TEST(LadderBlocks, AndLdOfTwoParallelBlocks) {
  // (X0 OR X1) AND (X2 OR X3 OR X4)
  const Network n = net0("ORG X0\nOR X1\nLD X2\nOR X3\nOR X4\nANDLD\nOUT Y0\nEND\n");
  EXPECT_EQ(n.rows, 3);
  EXPECT_EQ(n.cols, 2);
  EXPECT_TRUE(cell(n, "X1", 1, 0));
  EXPECT_TRUE(cell(n, "X2", 0, 1));
  EXPECT_TRUE(cell(n, "X4", 2, 1));
  EXPECT_TRUE(vwire(n, 0, 0, 1));
  EXPECT_TRUE(vwire(n, 1, 0, 1));  // the first block's right side
  EXPECT_TRUE(vwire(n, 1, 0, 2));  // the second block's left side: the same node
  EXPECT_TRUE(vwire(n, 2, 0, 2));
}

// A block nested `depth` deep, alternating ANDLD and ORLD: every contact in its own cell,
// inside the grid, and the output at the right of row 0.
TEST(LadderBlocks, DeepNestingStaysInsideTheGridWithoutOverlaps) {
  for (int depth = 1; depth <= 8; ++depth) {
    std::string il = "ORG M0\n";
    for (int k = 1; k <= depth; ++k) il += "LD M" + std::to_string(k) + "\nOR M" + std::to_string(100 + k) + "\n";
    for (int k = depth; k >= 1; --k) il += k % 2 ? "ANDLD\n" : "ORLD\n";
    il += "OUT Y0\nEND\n";
    const Network n = net0(il);
    ASSERT_TRUE(n.drawable) << n.reason;
    std::set<std::pair<int, int>> cells;
    for (const Element& e : n.elements) {
      EXPECT_TRUE(cells.insert({e.row, e.col}).second) << "depth " << depth << ": two elements at " << e.row;
      EXPECT_LT(e.row, n.rows);
      EXPECT_LE(e.col, n.cols);
      EXPECT_EQ(e.type == "contact", e.col < n.cols);
    }
    EXPECT_EQ(n.elements.size(), static_cast<size_t>(2 * depth + 2));
    EXPECT_TRUE(cell(n, "Y0", 0, n.cols));
  }
}

}  // namespace test
}  // namespace ladder
}  // namespace plc_cell
