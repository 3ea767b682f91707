// A simulation pulse train's edges (the cell YAML's `pulse:` on X0-X15): rising at
// delay + k * period, falling width later. The train keeps its last answer for the scans
// that follow, so it is asked here out of order too: every answer must be the edge the
// arithmetic gives for that instant.
#include <gtest/gtest.h>

#include <vector>

#include "plc_cell/hsc/pulse_train.h"

namespace plc_cell {
namespace hsc {
namespace {

TEST(PulseTrain, NextEdgeAfterAnyInstantInAnyOrder) {
  const PulseTrain tr{3, 100, 40, 10};  // X3: on 10-50, 110-150, ...
  struct Ask {
    uint64_t t, edge;
    bool rising;
  };
  const std::vector<Ask> asks = {{0, 10, true},    {9, 10, true},    {10, 50, false}, {49, 50, false},
                                 {50, 110, true},  {60, 110, true},  {20, 50, false}, {5, 10, true},
                                 {109, 110, true}, {110, 150, false}, {1000, 1010, true}, {30, 50, false}};
  for (const Ask& a : asks) {
    bool rising = !a.rising;
    EXPECT_EQ(tr.next_after(a.t, &rising), a.edge) << "t = " << a.t;
    EXPECT_EQ(rising, a.rising) << "t = " << a.t;
  }
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
