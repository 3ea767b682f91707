// The manual's chapter 11 examples under examples/motion/ through `plc_cell sim`,
// as a user runs them.
#include <gtest/gtest.h>

#include "../core/run_tool.h"


#include <cstdio>
#include <string>

namespace {

using Result = plc_cell::testing::ToolResult;
// The tool as a user runs it, with the suite's time limit (test/core/run_tool.h).
Result tool(const std::string& args) { return plc_cell::testing::run_tool(args); }

TEST(MotionCli, ManualExamplesRunWithSim) {
  struct Case {
    const char* name;
    const char* args;
    const char* expect;
  };
  const Case cases[] = {
      // B: 20000 + 60000 + 5000, waiting for X0 after step 3.
      {"drvc_chain", "--duration 6s --watch DR4088,R4064,M11", "DR4088 = 85000\nR4064 = 3\nM11 = 0\n"},
      // A: +10000 +3000, -6000 split by X0 into steps 3 and 4, X1 -> step 1: +10000.
      {"positioning", "--duration 10s --watch DR4088,R4064,M11", "DR4088 = 17000\nR4064 = 1\nM11 = 0\n"},
      // D: DRVZ MD2 ends with DR4088 = P16 = 100, the last step done.
      {"homing", "--duration 3s --watch DR4088,M1996,Y8,R4060", "DR4088 = 100\nM1996 = 1\nY8 = 0\nR4060 = 0\n"},
      // C: FUN147 steps 1-3, X0 at 5 s, step 1 again: +500 +400 +300 +200 on (1500, 900, 0, 600).
      {"interpolation", "--duration 6s --watch DR4088,DR4090,DR4092,DR4094,D4062,D4060",
       "DR4088 = 2000\nDR4090 = 1300\nDR4092 = 300\nDR4094 = 800\nD4062 = 1\nD4060 = 0\n"},
      // E: 100 wheel periods (0.2-1.2 s at 100 Hz) x100 on Ps1, then 140 (1.6-3.0 s) on Ps0;
      // both MPGs sampled the counter last at 240; WR+1 = EN << 8 | Ps.
      {"mpg", "--duration 3.5s --watch DR4088,DR4090,DD802,DD812,D801,D811",
       "DR4088 = 14000\nDR4090 = 10000\nDD802 = 240\nDD812 = 240\nD801 = 256\nD811 = 1\n"},
      // TRi Ch. 10: STEPSPEED 1,100,50, STEPMOVE +500 then -500: 2 x 5.765625 s; at 6 s the
      // first move is done (M101 on) and the second just started (M101 off, Y1 on: backward).
      {"stepper", "--duration 6s --watch R4064,M101,Y1", "R4064 = 1\nM101 = 0\nY1 = 1\n"},
      {"stepper", "--duration 12s --watch DR4088,R4064,M101,Y1,M11", "DR4088 = 0\nR4064 = 2\nM101 = 1\nY1 = 1\nM11 = 0\n"},
  };
  for (const auto& c : cases) {
    const Result r = tool("sim --config " + std::string(PLC_CELL_SOURCE_DIR) + "/examples/motion/" + c.name +
                          ".yaml " + c.args);
    EXPECT_EQ(r.status, 0) << c.name << "\n" << r.out;
    EXPECT_NE(r.out.find(c.expect), std::string::npos) << c.name << "\n" << r.out;
  }
}

// Example D without a CLR output (P15-3 = FFH), in each mode: the homing ends at
// step c (the manual) and the tool exits normally with the homed position.
TEST(MotionCli, HomingWithoutClrInEachMode) {
  for (const char* mode : {"MD0", "MD1", "MD2"}) {
    const std::string dir = ::testing::TempDir();
    const std::string yaml = dir + "/homing_noclr_" + mode + ".yaml";
    FILE* f = fopen(yaml.c_str(), "w");
    ASSERT_NE(f, nullptr);
    fprintf(f,
            "cell:\n  name: noclr\n  program: %s/examples/motion/homing.il\n"
            "axes:\n  pso0:\n"
            "    params: {at: R500, p8: 100, p9: 0x0100, p15: 0xFF04A802, p16: 100, p17: 10}\n"
            "    table:\n      at: R0\n      text: |\n        001 SPD 5000\n            DRVZ %s\n"
            "            GOTO NEXT\n        MEND\n"
            "    switches:\n      - {x: X2, from: -5000, to: -3000}\n      - {x: X40, from: -7999}\n"
            "      - {x: X4, period: 200, width: 5}\n",
            PLC_CELL_SOURCE_DIR, mode);
    fclose(f);
    const Result r = tool("sim --config " + yaml + " --duration 3s --watch DR4088,M1996,R4060,Y8");
    EXPECT_EQ(r.status, 0) << mode << "\n" << r.out;
    EXPECT_NE(r.out.find("DR4088 = 100\nM1996 = 1\nR4060 = 0\nY8 = 0\n"), std::string::npos) << mode << "\n" << r.out;
  }
}

// The test rig: pins looped into HSC0, an encoder into HSC1, a sensor on the stage.
TEST(MotionCli, TestRigCountsThePinsAndTheEncoder) {
  const Result r = tool("sim --config " + std::string(PLC_CELL_SOURCE_DIR) +
                        "/examples/motion/test_rig.yaml --duration 2s --watch DR4088,DR4096,DR4100,DR300,R302,Y2");
  EXPECT_EQ(r.status, 0) << r.out;
  // +10000 -4000; HSC0 = up - down pulses; HSC1 = 4 counts x 1 period per pulse x
  // 6000; HSC0I at CV = PV = 8000 going up and coming down; Y2 the ladder's output.
  EXPECT_NE(r.out.find("DR4088 = 6000\nDR4096 = 6000\nDR4100 = 24000\nDR300 = 8000\nR302 = 2\nY2 = 1\n"),
            std::string::npos)
      << r.out;
}

// A cell whose YAML table (under axes.<key>) is bad on its second text line.
Result bad_yaml_table(const std::string& name, const std::string& key, const std::string& line2) {
  const std::string dir = ::testing::TempDir();
  FILE* f = std::fopen((dir + "/" + name + ".il").c_str(), "w");
  std::fputs("ORG M1925\nOUT M0\nEND\n", f);
  std::fclose(f);
  f = std::fopen((dir + "/" + name + ".yaml").c_str(), "w");
  std::fputs(("cell: {program: " + name + ".il}\naxes:\n  " + key + ":\n    table:\n      at: R0\n      text: |\n"
              "        SPD 100\n        " + line2 + "\n        GOTO NEXT\n        MEND\n").c_str(),
             f);
  std::fclose(f);
  return tool("sim --config " + dir + "/" + name + ".yaml --duration 0.1s");
}

TEST(MotionCli, BadTableInTheYamlNamesItsLine) {
  const Result r = bad_yaml_table("bad_motion", "pso0", "DRV ADR,+,5,mm");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("bad_motion.yaml:8:"), std::string::npos) << r.out;  // the DRV line
  EXPECT_NE(r.out.find("error 34"), std::string::npos) << r.out;
}

TEST(MotionCli, BadGroupTableInTheYamlNamesItsLine) {
  const Result r = bad_yaml_table("bad_group", "gp0", "LIN ADR,5,5,5,5,mm");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find("bad_group.yaml:8:"), std::string::npos) << r.out;  // the LIN line
  EXPECT_NE(r.out.find("error 60"), std::string::npos) << r.out;
}

}  // namespace
