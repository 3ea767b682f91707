// Any program the parser accepts is laid out without throwing: each network is either a
// sound grid or not drawable with a reason.
#include <random>
#include <string>

#include "ladder_fixture.h"
#include "plc_cell/core/error.h"
#include "plc_cell/ladder/flow.h"

namespace plc_cell {
namespace ladder {
namespace test {

TEST(LadderRobustness, RandomInstructionSequencesNeverThrow) {
  static const char* const words[] = {"ORG X0", "ORG NOT M1", "LD X2", "LD TU X3", "AND M4", "AND TD X5",
                                      "OR X6",  "OR NOT M7",  "ANDLD", "ORLD",     "OUT Y0", "OUT NOT Y1",
                                      "SET Y2", "RST R3",     "TMR T5 10", "CTR C3 5", "MOV S=R0 D=R1",
                                      "JMP L1", "FOR 2",      "NEXT"};
  const int n_words = sizeof words / sizeof words[0];
  int parsed = 0, undrawable = 0;
  for (unsigned seed = 1; seed <= 5000; ++seed) {
    std::mt19937 rng(seed);
    std::string il = "ORG X0\n";
    const int lines = 2 + static_cast<int>(rng() % 12);
    for (int k = 0; k < lines; ++k) il += std::string(words[rng() % n_words]) + "\n";
    il += "LBL L1\nEND\n";
    Program p;
    try {
      p = parse_program(il, "r.il", functions());
    } catch (const SourceError&) {
      continue;
    }
    ++parsed;
    SCOPED_TRACE(il);
    Layout l;
    ASSERT_NO_THROW(l = layout(p, il, {}, &functions()));
    for (const Network& n : l.networks) {
      if (!n.drawable) {
        EXPECT_FALSE(n.reason.empty());
        ++undrawable;
        continue;
      }
      expect_a_sound_grid(n);
      const Values v;
      EXPECT_NO_THROW(flow(n, v.lookup(), v.lookup()));
    }
  }
  EXPECT_GT(parsed, 500);
  EXPECT_GT(undrawable, 0);
}

}  // namespace test
}  // namespace ladder
}  // namespace plc_cell
