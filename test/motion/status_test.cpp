// The axes' status registers and relays (docs/motion.md "Status"): what every scan shows
// of the axes, whoever else wrote into the block since, and the position the ladder
// gives an idle axis by writing DR4088.
#include "motion_fixture.h"

namespace plc_cell {
namespace motion {
namespace {

// M0 writes 12345 into Ps0's position, M1 writes 0 (the manual's homing methods 1 and 2).
constexpr const char* kLadderHoming = R"(ORG M0
MOV.D S=12345 D=DR4088
ORG M1
MOV.D S=0 D=DR4088
END
)";

// The manual (Ps0 status: "set the value 100 to DR4088"; homing methods 1 and 2 write 0):
// the current position register can be written by the ladder. A write in the program
// scan sets the idle axis there, and the status written after the program shows it.
TEST(AxisStatus, ALadderWriteOfDr4088InTheScanSetsTheIdleAxisPosition) {
  MotionCell c(kLadderHoming);
  c.run(3000);
  ASSERT_EQ(c.get32("DR4088"), 0);
  c.put("M0", 1);
  c.run(1000);
  EXPECT_EQ(c.get32("DR4088"), 12345);
  EXPECT_EQ(c.with([](MotionUnit& u) { return u.position(0); }), 12345);
  c.put("M0", 0);
  c.run(5000);  // scans with nothing written keep it
  EXPECT_EQ(c.get32("DR4088"), 12345);
  c.put("M1", 1);
  c.run(1000);
  EXPECT_EQ(c.get32("DR4088"), 0);
  EXPECT_EQ(c.with([](MotionUnit& u) { return u.position(0); }), 0);
}

// The read-only part of the block (frequency DR4080, pulses left DR4072, the relays) is
// the unit's: what a client writes there between scans is put back at the next scan,
// also while nothing moves and every scan would write the same values.
TEST(AxisStatus, AClientWriteIntoTheBlockOfAnIdleUnitIsPutBackAtTheNextScan) {
  MotionCell c;
  c.run(5000);
  ASSERT_EQ(c.get("M1992"), 1u);  // ready: no program holds Ps0
  ASSERT_EQ(c.get32("DR4080"), 0);
  c.put("DR4080", 777);
  c.put("DR4074", 5);
  c.put("M1992", 0);
  c.put("M1997", 1);
  c.run(1000);
  EXPECT_EQ(c.get32("DR4080"), 0);
  EXPECT_EQ(c.get32("DR4074"), 0);
  EXPECT_EQ(c.get("M1992"), 1u);
  EXPECT_EQ(c.get("M1997"), 0u);
  // The vector speeds of FUN147 (DR4068, DR4070) and its done relays, the same way.
  c.put("DR4068", 9);
  c.put("M1934", 1);
  c.run(1000);
  EXPECT_EQ(c.get32("DR4068"), 0);
  EXPECT_EQ(c.get("M1934"), 0u);
}

// A forced (disabled) status relay keeps its forced state through the scans' status
// writes, and shows the unit's state again once enabled.
TEST(AxisStatus, AForcedReadyRelayKeepsItsStateUntilEnabled) {
  MotionCell c;
  c.run(3000);
  const Address ready = parse_address("M1993");
  c.plc.force(ready, ForceAction::Disable);
  c.plc.force(ready, ForceAction::Reset);
  c.run(5000);
  EXPECT_EQ(c.get("M1993"), 0u);
  c.plc.force(ready, ForceAction::Enable);
  c.run(1000);
  EXPECT_EQ(c.get("M1993"), 1u);
}

// What changes the axes between scans without the ladder (a ROS service, the run action)
// shows at the next scan though no axis moves: the unit's own state, not the memory,
// changed.
TEST(AxisStatus, AChangeMadeBetweenScansShowsAtTheNextScan) {
  MotionCell c;
  c.run(3000);
  c.with([](MotionUnit& u) {
    u.set_rest(2, 4321);
    u.take_axis(3, 7);
    return 0;
  });
  c.run(1000);
  EXPECT_EQ(c.get32("DR4076"), 4321);  // Ps2's pulses left
  EXPECT_EQ(c.get("M1995"), 0u);       // Ps3 held: not ready
  c.with([](MotionUnit& u) {
    u.release_axis(3, 7);
    u.drive(1).set_position(-50);
    return 0;
  });
  c.run(1000);
  EXPECT_EQ(c.get("M1995"), 1u);
  EXPECT_EQ(c.get32("DR4090"), -50);  // Ps1's position
}

// A FUN140 move ends, and the unit, idle again, shows the final position and no
// frequency from then on, scan after scan.
TEST(AxisStatus, AfterAMoveTheIdleStatusStaysTheMovesEnd) {
  MotionCell c;
  c.params(fast_params());
  c.table("SPD 5000\nDRV ADR,+,1000,Ps\nGOTO NEXT\nMEND\n");
  c.run(2000);
  c.put("M1", 1);
  ASSERT_TRUE(c.run_until([&] { return c.get("M12") == 1; }, 2000000));
  c.run(3000);
  EXPECT_EQ(c.get32("DR4088"), 1000);
  EXPECT_EQ(c.get32("DR4080"), 0);
  EXPECT_EQ(c.get("M1996"), 1u);
  c.put("DR4080", 1);
  c.run(1000);
  EXPECT_EQ(c.get32("DR4080"), 0);
  EXPECT_EQ(c.get32("DR4088"), 1000);
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell
