// Tables run by the unit itself (what the ROS services and action use).
#include <cmath>

#include "motion_fixture.h"

namespace plc_cell {
namespace motion {
namespace {

constexpr const char* kNoLadder = "ORG M1925\nMPARA Ps=1 SR=R2000\nEND\n";

Table parse(const std::string& text) {
  Table t;
  TableError e;
  EXPECT_TRUE(parse_table(text, &t, &e)) << e.message;
  return t;
}

TEST(ExternalControl, StartRunsTheTableToItsEnd) {
  MotionCell c(kNoLadder);
  c.params(fast_params());
  c.run(1000);  // MPARA has run
  std::string why;
  const bool ok = c.with([&](MotionUnit& u) {
    return u.load_table(1, parse("SPD 10000\nDRV ADR,+,5000,Ps\nGOTO NEXT\nSPD 10000\nDRV ADR,-,2000,Ps\nGOTO NEXT\nMEND"), &why) &&
           u.command(1, MotionUnit::Command::Start, &why);
  });
  ASSERT_TRUE(ok) << why;
  c.run(1000);
  EXPECT_TRUE(c.with([](MotionUnit& u) { return u.program_running(1); }));
  ASSERT_TRUE(c.run_until([&] { return c.get("M1997") == 1; }, 5000000));
  EXPECT_EQ(c.get32("DR4090"), 3000);
  EXPECT_FALSE(c.with([](MotionUnit& u) { return u.program_running(1); }));
  ASSERT_EQ(c.done.size(), 2u);
  // Again from the first step.
  ASSERT_TRUE(c.with([&](MotionUnit& u) { return u.command(1, MotionUnit::Command::Start, &why); })) << why;
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 4; }, 5000000));
  EXPECT_EQ(c.done[2].step, 1);
  EXPECT_EQ(c.get32("DR4090"), 6000);
}

TEST(ExternalControl, AbortDeceleratesEvenWithM1991Off) {
  MotionCell c(kNoLadder);
  c.params(fast_params());
  c.run(1000);  // MPARA has run
  std::string why;
  ASSERT_TRUE(c.with([&](MotionUnit& u) {
    return u.load_table(1, parse("SPD 100000\nDRV ADR,+,10000000,Ps\nGOTO NEXT\nMEND"), &why) &&
           u.command(1, MotionUnit::Command::Start, &why);
  }));
  c.run(200000);
  EXPECT_EQ(c.get32("DR4082"), 100000);
  const int32_t at = c.with([&](MotionUnit& u) {
    u.command(1, MotionUnit::Command::Abort, &why);
    return static_cast<int32_t>(u.axis(1).position(u.now_ns()));
  });
  c.run(1000);
  EXPECT_GT(c.get32("DR4082"), 0);  // still slowing down
  c.run(100000);
  EXPECT_EQ(c.get32("DR4082"), 0);
  const double d = (1e10 - 141.0 * 141) / (2 * 4.6e6);
  EXPECT_EQ(c.get32("DR4090") - at, static_cast<int32_t>(std::ceil(d)));
  EXPECT_TRUE(c.done.empty());
}

TEST(ExternalControl, PauseAndResume) {
  MotionCell c(kNoLadder);
  c.params(fast_params());
  c.run(1000);  // MPARA has run
  std::string why;
  ASSERT_TRUE(c.with([&](MotionUnit& u) {
    return u.load_table(1, parse("SPD 10000\nDRV ADR,+,20000,Ps\nGOTO NEXT\nMEND"), &why) &&
           u.command(1, MotionUnit::Command::Start, &why);
  }));
  c.run(500000);
  c.with([&](MotionUnit& u) { return u.command(1, MotionUnit::Command::Pause, &why); });
  c.run(2000);
  const int32_t p = c.get32("DR4090");
  c.run(300000);
  EXPECT_EQ(c.get32("DR4090"), p);
  c.with([&](MotionUnit& u) { return u.command(1, MotionUnit::Command::Resume, &why); });
  ASSERT_TRUE(c.run_until([&] { return c.done.size() == 1; }, 5000000));
  EXPECT_EQ(c.get32("DR4090"), 20000);
}

TEST(ExternalControl, RefusedWhileALadderFun140HoldsTheAxis) {
  MotionCell c;  // the ladder FUN140 on axis 0
  c.params(fast_params());
  c.table("SPD 1000\nDRV ADR,+,100000,Ps\nGOTO NEXT\nMEND\n");
  c.put("M1", 1);
  c.run(2000);
  std::string why;
  EXPECT_FALSE(c.with([&](MotionUnit& u) { return u.load_table(0, parse("SPD 1\nDRV ADR,+,1,Ps\nGOTO NEXT\nMEND"), &why); }));
  EXPECT_NE(why.find("FUN140"), std::string::npos);
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell
