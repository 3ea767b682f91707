// PSO0I-PSO3I at the exact instant of each step's end, in the cell's scheduler
// (docs/counters-and-interrupts.md, "Plugging in the pulse-output axes").
#include "motion_fixture.h"
#include "plc_cell/timeline/scheduler.h"

namespace plc_cell {
namespace motion {
namespace {

constexpr const char* kProgram = R"(ORG M1925
MPARA Ps=0 SR=R2000
ORG M1
LD M2
LD M3
HSPSO Ps=0 SR=R0 WR=R100 ACT=M10 ERR=M11 DN=M12
END
LBL PSO0I
ORG M1925
INC D=R300
MOV.D S=DR4088 D=DR302
RTI
)";

class PsoInterrupt : public ::testing::TestWithParam<bool> {};

// With or without a counter unit: the axes and the counters share one scheduler, which
// whichever comes first makes.
TEST_P(PsoInterrupt, RunsAtEachStepsExactEndInstant) {
  MotionCell c(kProgram, /*with_counters=*/GetParam());
  c.params(fast_params());
  c.table("SPD 7000\nDRV ADR,+,1234,Ps\nWAIT Time,3\nGOTO NEXT\nSPD 3000\nDRV ADR,-,777,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.get("M1996") == 1; }, 5000000));
  ASSERT_EQ(c.done.size(), 2u);
  ASSERT_EQ(c.isrs.size(), 2u);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(c.isrs[i].second, irq::kPso0I);
    EXPECT_EQ(c.isrs[i].first, c.done[i].t_ns);  // the same ns, not the next scan
    EXPECT_NE(c.isrs[i].first % 1000000, 0u) << "an end instant that falls on a scan would prove nothing";
  }
  EXPECT_EQ(c.get("R300"), 2u);
  EXPECT_EQ(c.get32("DR302"), 1234 - 777);  // the routine saw the position of its instant
  // Step 2 started 30 ms after step 1's end, exactly.
  const double d = (3000.0 * 3000 - 141.0 * 141) / (2 * 4.6e6);
  const double t2 = 2 * (3000 - 141) / 4.6e6 + (777 - 2 * d) / 3000;
  EXPECT_NEAR((c.done[1].t_ns - c.done[0].t_ns) * 1e-9, 0.03 + t2, 1e-8);
}

INSTANTIATE_TEST_SUITE_P(Counters, PsoInterrupt, ::testing::Bool());

}  // namespace
}  // namespace motion
}  // namespace plc_cell
