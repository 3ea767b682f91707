// The examples under examples/hsc/ through `plc_cell sim`, as a user runs them,
// and the FP-08 configuration error as the tool reports it.
#include <gtest/gtest.h>

#include "../core/run_tool.h"

#include <cstdio>
#include <fstream>
#include <string>

namespace {

using Result = plc_cell::testing::ToolResult;
Result tool(const std::string& args) { return plc_cell::testing::run_tool(args); }

std::string example(const std::string& name) {
  return std::string(PLC_CELL_SOURCE_DIR) + "/examples/hsc/" + name + ".yaml";
}

TEST(HscCli, ExamplesRunWithSim) {
  struct Case {
    const char* name;
    const char* args;
    const char* expect;
  };
  const Case cases[] = {
      {"cutting", "--duration 1.5s --watch feed_motor,DR4096", "feed_motor = 0\nDR4096 = 4400\n"},
      {"count_up_stop", "--duration 0.2s --watch motor,DR4096", "motor = 0\nDR4096 = 100000\n"},
      {"multi_zone", "--duration 1s --watch WY8,R0", "WY8 = 16\nR0 = 4\n"},
      {"rpm", "--duration 3s --watch R100", "R100 = 1500\n"},
      {"drill", "--duration 1s --watch DR0,M11", "DR0 = 12\nM11 = 0\n"},
  };
  for (const auto& c : cases) {
    const Result r = tool("sim --config " + example(c.name) + " " + c.args);
    EXPECT_EQ(r.status, 0) << c.name << "\n" << r.out;
    EXPECT_NE(r.out.find(c.expect), std::string::npos) << c.name << "\n" << r.out;
  }
}

TEST(HscCli, Fp08DoubleUseIsAConfigurationError) {
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/fp08.il") << "ORG M1925\nOUT M0\nEND\n";
  std::ofstream(dir + "/fp08.yaml") << "cell: {program: fp08.il}\n"
                                       "counters:\n"
                                       "  hsc1: {type: timer}\n"
                                       "  hsc2: {mode: MD7, mask: true, invert: [mask]}\n"
                                       "  hsc3: {mode: MD2, b: X13}\n"
                                       "  hsc6: {mode: MD0, a: X10, b: X2}\n";
  const Result r = tool("sim --config " + dir + "/fp08.yaml --duration 1s");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("fp08.yaml:6:24: error: key 'counters.hsc6.a': X10 is already used as the MASK input "
                       "of HSC2 (line 4)"),
            std::string::npos)
      << r.out;
}

}  // namespace
