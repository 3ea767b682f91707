// Where an axis's FUN141 parameters come from besides a ladder MPARA (docs/motion.md
// "Parameters from the cell YAML and from ROS"): the cell YAML's params: configure the
// axis from the start, and the ROS set_params service changes some of them by name.
#include <yaml-cpp/yaml.h>

#include "motion_fixture.h"
#include "plc_cell/core/error.h"
#include "plc_cell/motion/axis_config.h"

namespace plc_cell {
namespace motion {
namespace {

constexpr const char* kNoMpara = "ORG M1925\nOUT M0\nEND\n";

// A move started as the ROS services start one: the unit runs the table itself.
void start(MotionCell& c, const std::string& text) {
  Table t;
  TableError e;
  ASSERT_TRUE(parse_table(text, &t, &e)) << e.message;
  std::string why;
  ASSERT_TRUE(c.with([&](MotionUnit& u) { return u.load_table(0, t, &why) && u.command(0, MotionUnit::Command::Start, &why); }))
      << why;
}

double frequency(MotionCell& c) {
  return c.with([](MotionUnit& u) { return u.frequency(0); });
}

TEST(ParamUpdates, YamlParamsRampAMoveStartedWithoutMpara) {
  // P8 = 100 ms: 460 kHz / 0.1 s = 4.6 MHz/s, so 141 Hz -> 100 kHz takes 21.7 ms; with
  // the manual's default P8 = 5000 ms (92 kHz/s) the axis would be at 9341 Hz after 0.1 s.
  MotionCell c(kNoMpara);
  c.unit->configure(parse_axes_config(YAML::Load("axes:\n  pso0: {params: {p8: 100}}\n")["axes"], "cell.yaml"));
  c.run(1000);
  start(c, "SPD 100000\nDRV ADR,+,10000000,Ps\nGOTO NEXT\nMEND");
  c.run(10000);
  EXPECT_GT(frequency(c), 40000.0);
  c.run(90000);
  EXPECT_EQ(frequency(c), 100000.0);
  EXPECT_EQ(c.with([](MotionUnit& u) { return u.params(0).p8_acc_ms; }), 100);
  // Without at: no register image: R2000 on stays the program's.
  EXPECT_EQ(c.get("R2011"), 0u);
}

TEST(ParamUpdates, WithAtTheImageIsWrittenAndALadderMparaStillDecides) {
  // The image at R2000 holds P8 = 100 (R2011, the manual's layout); the ladder's MPARA
  // reads it every scan, after the program changed it: the ladder's value is the axis's.
  MotionCell c("ORG M1925\nMPARA Ps=0 SR=R2000 ERR=M13\nEND\n");
  c.unit->configure(parse_axes_config(YAML::Load("axes:\n  pso0: {params: {at: R2000, p8: 100}}\n")["axes"], "cell.yaml"));
  c.run(1000);
  EXPECT_EQ(c.get("R2011"), 100u);
  EXPECT_EQ(c.with([](MotionUnit& u) { return u.params(0).p8_acc_ms; }), 100);
  c.put("R2011", 250);
  c.run(1000);
  EXPECT_EQ(c.with([](MotionUnit& u) { return u.params(0).p8_acc_ms; }), 250);
}

TEST(ParamUpdates, YamlParamsAreAMapping) {
  try {
    parse_axes_config(YAML::Load("axes:\n  pso0: {params: 5}\n")["axes"], "cell.yaml");
    FAIL() << "accepted params: 5";
  } catch (const SourceError& e) {
    EXPECT_NE(std::string(e.what()).find("cell.yaml:2:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("axes.pso0.params"), std::string::npos) << e.what();
  }
}

TEST(ParamUpdates, NamedValuesChangeOnlyThoseParameters) {
  std::vector<std::pair<int, int64_t>> ch;
  std::string why;
  ASSERT_TRUE(param_changes({"p8", "P12"}, {100, 200}, &ch, &why)) << why;
  AxisParams p;
  p.p4_max = 300000;  // the axis's present value, kept
  AxisParams out;
  ParamError e;
  ASSERT_TRUE(p.updated(ch, &out, &e)) << e.message;
  EXPECT_EQ(out.p8_acc_ms, 100);
  EXPECT_EQ(out.p12_dec_ms, 200);
  EXPECT_EQ(out.p4_max, 300000);
  EXPECT_EQ(out.p1_ppr, 2000u);
}

TEST(ParamUpdates, ABadUpdateIsRefusedWhole) {
  std::vector<std::pair<int, int64_t>> ch;
  std::string why;
  ASSERT_TRUE(param_changes({"p12", "p8"}, {200, 30001}, &ch, &why)) << why;
  const AxisParams p;
  AxisParams out;
  out.p12_dec_ms = 7;
  ParamError e;
  EXPECT_FALSE(p.updated(ch, &out, &e));
  EXPECT_EQ(e.code, 9);
  EXPECT_EQ(e.message, "P8: 30001 out of range 0..30000");
  EXPECT_EQ(out.p12_dec_ms, 7);  // untouched
  // P0 = 0 (machine units) makes the present P4 = 460000 a machine speed: P4's range then.
  ASSERT_TRUE(param_changes({"p0"}, {0}, &ch, &why));
  EXPECT_FALSE(p.updated(ch, &out, &e));
  EXPECT_EQ(e.code, 5);
}

TEST(ParamUpdates, RequestsThatNameNoParameterAreRefused) {
  std::vector<std::pair<int, int64_t>> ch;
  std::string why;
  EXPECT_FALSE(param_changes({"p18"}, {1}, &ch, &why));
  EXPECT_EQ(why, "'p18': no such parameter (p0 ... p17)");
  EXPECT_FALSE(param_changes({"p08"}, {1}, &ch, &why));
  EXPECT_FALSE(param_changes({"speed"}, {1}, &ch, &why));
  EXPECT_FALSE(param_changes({"p8", "P8"}, {1, 2}, &ch, &why));
  EXPECT_EQ(why, "P8 given twice");
  EXPECT_FALSE(param_changes({"p8"}, {1, 2}, &ch, &why));
  EXPECT_EQ(why, "1 names but 2 values: one value per name");
  EXPECT_FALSE(param_changes({}, {1, 2}, &ch, &why));
  EXPECT_EQ(why, "give the 18 values P0..P17 in order, or names with their values (names: [p8], values: [100]); "
                 "got 2 values and no names");
  // The 18 values unnamed, as before.
  ASSERT_TRUE(param_changes({}, std::vector<int64_t>(18, 1), &ch, &why));
  EXPECT_EQ(ch.size(), 18u);
  EXPECT_EQ(ch[17], std::make_pair(17, int64_t(1)));
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell
