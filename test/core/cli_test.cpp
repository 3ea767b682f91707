// The plc_cell command-line tool, run as a user would run it.
#include <gtest/gtest.h>

#include "run_tool.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace {

using Result = plc_cell::testing::ToolResult;
Result tool(const std::string& args) { return plc_cell::testing::run_tool(args); }

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

const std::string kDemo = std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/conveyor.yaml";

}  // namespace

TEST(Cli, SimPrintsTheWatchedValuesAndIsDeterministic) {
  const std::string args = "sim --config " + kDemo +
                           " --duration 12s --watch conveyor_run,R0,T50 --trace /tmp/plc_cell_cli_test_";
  const Result a = tool(args + "a.csv");
  const Result b = tool(args + "b.csv");
  ASSERT_EQ(a.status, 0) << a.out;
  EXPECT_EQ(a.out, b.out);
  EXPECT_EQ(slurp("/tmp/plc_cell_cli_test_a.csv"), slurp("/tmp/plc_cell_cli_test_b.csv"));
  EXPECT_EQ(a.out,
            "# plc_cell sim: 12000 scans of 1000 us, virtual time 12.000000 s, RUN\n"
            "conveyor_run = 0\n"
            "R0 = 2\n"
            "T50 = 0\n");
  const std::string trace = slurp("/tmp/plc_cell_cli_test_a.csv");
  EXPECT_EQ(trace.rfind("time_s,address,value,event,source\n0.000000,conveyor_run,1\n0.000000,R0,0\n0.000000,T50,0\n"
                        "1.000000,conveyor_run,0\n2.500000,T50,1\n2.501000,conveyor_run,1\n",
                        0),
            0u)
      << trace;
  EXPECT_NE(trace.find("8.501000,R0,2\n"), std::string::npos);
}

TEST(Cli, SimSetsAddressesBeforeTheRun) {
  const std::string prog = "/tmp/plc_cell_cli_add.il";
  std::ofstream(prog) << "ORG M1925\nADD Sa=R1 Sb=R2 D=R3\nORG X0\nOUT Y0\nEND\n";
  const Result r = tool("sim --program " + prog + " --duration 10ms --scan 2ms --set R1=40 --set R2=0x2 --set X0=1 --watch R3,Y0");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "# plc_cell sim: 5 scans of 2000 us, virtual time 0.010000 s, RUN\nR3 = 42\nY0 = 1\n");
}

TEST(Cli, CheckListsEveryErrorAndFails) {
  const std::string prog = "/tmp/plc_cell_cli_bad.il";
  std::ofstream(prog) << "ORG X0\nOUT Q1\nTMR T1\nEND\n";
  const Result r = tool("check --program " + prog);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find(prog + ":2:5: error: bad address 'Q1'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(prog + ":3:1: error: TMR takes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2 error(s)"), std::string::npos);
  const Result ok = tool("check --program " + std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/conveyor.il");
  EXPECT_EQ(ok.status, 0) << ok.out;
  EXPECT_NE(ok.out.find("OK, 27 instructions"), std::string::npos) << ok.out;
}

TEST(Cli, UsageErrorsExitWithTwo) {
  EXPECT_EQ(tool("").status, 2);
  EXPECT_EQ(tool("frobnicate").status, 2);
  const Result r = tool("sim --config " + kDemo);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("missing --duration"), std::string::npos);
  EXPECT_EQ(tool("sim --bogus 1").status, 2);
  const Result bad = tool("sim --config " + kDemo + " --duration 1s --watch Q7");
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.out.find("'Q7' is neither a signal"), std::string::npos) << bad.out;
}

TEST(Cli, RunStopsAfterItsDuration) {
  const Result r = tool("run --config " + kDemo + " --duration 300ms");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("scans, cycle avg"), std::string::npos) << r.out;
}

TEST(Cli, RunRejectsABadPriority) {
  const Result r = tool("run --config " + kDemo + " --duration 10ms --rt-priority high");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("--rt-priority takes a whole number, got 'high'"), std::string::npos) << r.out;
  EXPECT_EQ(tool("run --config " + kDemo + " --duration 10ms --rt-priority 100").status, 2);
}

TEST(Cli, CheckKnowsEveryInstalledFunction) {
  const std::string prog = "/tmp/plc_cell_cli_funs.il";
  std::ofstream(prog) << "ORG M0\nLD M1\nLD M2\nFUN 151 Pt=1 MD=0 SR=R100 WR=R200 ACT=Y0 ERR=Y1 DN=Y2\n"
                         "ORG M3\nLD M4\nLD M5\nFUN 150 Pt=2 SR=R300 WR=R400 ACT=M10 ERR=M11 DN=M12\nEND\n";
  const Result r = tool("check --program " + prog);
  EXPECT_EQ(r.status, 0) << r.out;
}
