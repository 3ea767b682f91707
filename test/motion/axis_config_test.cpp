// The cell YAML's axes: section and the positional switches.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "plc_cell/core/error.h"
#include "plc_cell/motion/axis_config.h"

namespace plc_cell {
namespace motion {
namespace {

TEST(AxisConfig, ParsesNamesModesMechanicsAndSwitches) {
  const YAML::Node doc = YAML::Load(R"(axes:
  pso0:
    name: slide
    output: UD
    type: linear
    units_per_pulse: 0.00001
    switches:
      - {x: X2, from: -5000, to: -3000}
      - {x: X4, period: 200, width: 5}
  pso2: {name: table, type: rotary, units_per_pulse: 0.0031416}
)");
  const AxesConfig c = parse_axes_config(doc["axes"], "cell.yaml");
  EXPECT_TRUE(c.axes[0].used);
  EXPECT_FALSE(c.axes[1].used);
  EXPECT_EQ(c.axes[0].name, "slide");
  EXPECT_EQ(c.axes[0].mode, OutputMode::UD);
  EXPECT_DOUBLE_EQ(c.axes[0].units_per_pulse, 1e-5);
  ASSERT_EQ(c.axes[0].switches.size(), 2u);
  EXPECT_EQ(c.axes[0].switches[1].x, 4);
  EXPECT_TRUE(c.axes[2].rotary);
  EXPECT_EQ(c.axes[2].mode, OutputMode::PR);  // default
}

// joint_states are in m or rad: si_per_pulse when given, else units_per_pulse (the
// user unit taken to be m or rad).
TEST(AxisConfig, JointScaleIsSiPerPulseOrUnitsPerPulse) {
  const YAML::Node doc = YAML::Load(R"(axes:
  pso0: {name: slide, units_per_pulse: 0.001, si_per_pulse: 0.000001}
  pso1: {name: stage, units_per_pulse: 0.00001}
)");
  const AxesConfig c = parse_axes_config(doc["axes"], "cell.yaml");
  EXPECT_DOUBLE_EQ(c.axes[0].units_per_pulse, 1e-3);
  EXPECT_DOUBLE_EQ(c.axes[0].joint_scale(), 1e-6);
  EXPECT_DOUBLE_EQ(c.axes[1].joint_scale(), 1e-5);
  EXPECT_THROW(parse_axes_config(YAML::Load("axes:\n  pso0: {si_per_pulse: 0}\n")["axes"], "c"), SourceError);
}

TEST(AxisConfig, BadKeysNameTheirLine) {
  try {
    parse_axes_config(YAML::Load("axes:\n  pso0:\n    name: a\n    outputs: UD\n")["axes"], "cell.yaml");
    FAIL() << "no error";
  } catch (const SourceError& e) {
    EXPECT_NE(std::string(e.what()).find("cell.yaml:4"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("axes.pso0.outputs"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_axes_config(YAML::Load("axes:\n  pso4: {}\n")["axes"], "c"), SourceError);
  EXPECT_THROW(parse_axes_config(YAML::Load("axes:\n  pso0: {switches: [{x: Y2}]}\n")["axes"], "c"), SourceError);
  EXPECT_THROW(parse_axes_config(YAML::Load("axes:\n  pso0: {units_per_pulse: 0}\n")["axes"], "c"), SourceError);
}

// An axis's name becomes its topics (~motion/<name>/...): letters, digits and _.
TEST(AxisConfig, AnAxisNameIsATopicName) {
  try {
    parse_axes_config(YAML::Load("axes:\n  pso1:\n    name: x axis\n")["axes"], "cell.yaml");
    FAIL() << "no error";
  } catch (const SourceError& e) {
    EXPECT_STREQ(e.what(), "cell.yaml:3:11: error: key 'axes.pso1.name': an axis name is letters, digits and _ "
                           "(it becomes a ROS topic name)");
  }
  EXPECT_EQ(parse_axes_config(YAML::Load("axes:\n  pso1: {name: x_axis2}\n")["axes"], "cell.yaml").axes[1].name, "x_axis2");
}

// axes: is read by the cell's YAML reader: values get its messages and positions.
TEST(AxisConfig, ValuesAreReadByTheCellsReader) {
  const auto error = [](const std::string& yaml) {
    try {
      parse_axes_config(YAML::Load(yaml)["axes"], "cell.yaml");
    } catch (const SourceError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("axes:\n  pso0: {units_per_pulse: fast}\n"),
            "cell.yaml:2:27: error: key 'axes.pso0.units_per_pulse': expected a number");
  EXPECT_EQ(error("axes:\n  pso0: {encoder: {a: X0, periods_per_pulse: 1.5}}\n"),
            "cell.yaml:2:46: error: key 'axes.pso0.encoder.periods_per_pulse': expected a whole number");
  EXPECT_EQ(error("axes:\n  pso0: {output: XY}\n"), "cell.yaml:2:18: error: key 'axes.pso0.output': expected UD, PR or AB");
}

TEST(AxisConfig, SwitchLevelsAndNextChanges) {
  SwitchDef w;
  w.from = -5000;
  w.to = -3000;
  EXPECT_FALSE(w.level(-2999));
  EXPECT_TRUE(w.level(-3000));
  EXPECT_EQ(w.next_change(0, -1), -3000);
  EXPECT_EQ(w.next_change(-3000, -1), -5001);
  EXPECT_EQ(w.next_change(-5001, +1), -5000);
  EXPECT_EQ(w.next_change(-4000, +1), -2999);
  SwitchDef pg;
  pg.period = 200;
  pg.width = 5;
  EXPECT_TRUE(pg.level(-200));
  EXPECT_TRUE(pg.level(-196));
  EXPECT_FALSE(pg.level(-195));
  EXPECT_EQ(pg.next_change(-3000, -1), -3001);   // leaves the pulse at -3000
  EXPECT_EQ(pg.next_change(-3001, -1), -3196);   // next rising edge moving down
  EXPECT_EQ(pg.next_change(-3196, +1), -3195);
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell
