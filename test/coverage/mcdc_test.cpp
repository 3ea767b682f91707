// MC/DC in its unique-cause form (docs/coverage.md): a contact is shown when two scans
// differ in it alone and in the network's outcome; seeing it ON and OFF is not enough.
#include "coverage_fixture.h"

namespace plc_cell {
namespace coverage {
namespace {

using Mcdc = CoverageTest;

// Y0 = X0 AND X1; Y1 = X2 OR X3, then AND X4.
const char* const kProgram =
    "ORG X0\n"
    "AND X1\n"
    "OUT Y0\n"
    "ORG X2\n"
    "OR X3\n"
    "AND X4\n"
    "OUT Y1\n"
    "END\n";

TEST_F(Mcdc, ConditionCoverageIsNotEnoughEachContactMustDecideItsNetworkAlone) {
  const std::string path = write("and.il", kProgram);
  Recorder both_ways;
  // (1,1) then (0,0): X0 and X1 each seen ON and OFF, but never alone changed Y0.
  run_case(both_ways, path, {{{0, true}, {1, true}}, {{0, false}, {1, false}}});
  Report r = report(both_ways);
  EXPECT_TRUE(item(r, 1).exercised() && item(r, 2).exercised());
  EXPECT_FALSE(item(r, 1).mcdc);
  EXPECT_FALSE(item(r, 2).mcdc);
  // (1,1), (0,1), (1,0): the unique-cause pairs of AND, in a second case of the same run.
  run_case(both_ways, path, {{{0, true}, {1, true}}, {{0, false}}, {{0, true}, {1, false}}});
  r = report(both_ways);
  EXPECT_TRUE(item(r, 1).mcdc);
  EXPECT_TRUE(item(r, 2).mcdc);
  EXPECT_EQ(r.totals.contacts_mcdc, 2u);
}

TEST_F(Mcdc, APairNeedsTheOutcomeToChange) {
  const std::string path = write("or.il", kProgram);
  Recorder rec;
  // X4 OFF: Y1 stays OFF whatever X2 and X3 do, so no pair counts for them; X4 itself
  // flips Y1 with X2 ON: shown.
  run_case(rec, path, {{{2, false}, {3, false}, {4, false}}, {{2, true}}, {{3, true}}, {{2, false}},
                       {{4, true}}, {{4, false}}});
  const Report r = report(rec);
  EXPECT_FALSE(item(r, 4).mcdc);  // X2
  EXPECT_FALSE(item(r, 5).mcdc);  // X3
  EXPECT_TRUE(item(r, 6).mcdc);   // X4: (X2 OFF, X3 ON, X4 OFF -> Y1 OFF) and (.., X4 ON -> Y1 ON)
}

}  // namespace
}  // namespace coverage
}  // namespace plc_cell
