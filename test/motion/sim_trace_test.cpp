// `plc_cell sim --trace` event rows and `--watch` formats, through the tool as a
// user runs it (docs/command-line.md "plc_cell sim").
#include <gtest/gtest.h>

#include "../core/run_tool.h"


#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using Result = plc_cell::testing::ToolResult;
// The tool as a user runs it, with the suite's time limit (test/core/run_tool.h).
Result tool(const std::string& args) { return plc_cell::testing::run_tool(args); }

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string example(const std::string& dir, const std::string& name) {
  return std::string(PLC_CELL_SOURCE_DIR) + "/examples/" + dir + "/" + name + ".yaml";
}

struct Row {
  std::string time, address, value, event, source;
  int fields;
};

std::vector<Row> rows(const std::string& csv) {
  std::vector<Row> r;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::string cell;
    std::istringstream ls(line);
    while (std::getline(ls, cell, ',')) f.push_back(cell);
    if (!line.empty() && line.back() == ',') f.push_back("");
    Row row{};
    row.fields = static_cast<int>(f.size());
    std::string* slots[] = {&row.time, &row.address, &row.value, &row.event, &row.source};
    for (size_t i = 0; i < f.size() && i < 5; ++i) *slots[i] = f[i];
    r.push_back(row);
  }
  return r;
}

std::vector<Row> events(const std::vector<Row>& all, const std::string& kind) {
  std::vector<Row> r;
  for (const auto& x : all)
    if (x.event == kind) r.push_back(x);
  return r;
}

// Manual 10.5-2 count-up stop: HSC0 reaches PV = 100000 at 1.84 M counts/s; the
// example test (ExampleFiles.CountUpStop) has Y0 fall at 54347827 ns, the CV=PV instant.
TEST(SimTrace, HscCvEqualsPvAndItsInterruptAtTheExactInstant) {
  const std::string csv = ::testing::TempDir() + "/sim_trace_hsc.csv";
  const Result r = tool("sim --config " + example("hsc", "count_up_stop") +
                        " --duration 0.2s --watch motor,DR4096 --trace " + csv);
  ASSERT_EQ(r.status, 0) << r.out;
  const std::string text = slurp(csv);
  EXPECT_EQ(text.rfind("time_s,address,value,event,source\n0.000000,motor,1\n0.000000,DR4096,0\n", 0), 0u) << text;
  const auto all = rows(text);
  const auto cv = events(all, "cv=pv");
  ASSERT_EQ(cv.size(), 1u) << text;
  EXPECT_EQ(cv[0].time, "0.054347827");
  EXPECT_EQ(cv[0].source, "HSC0");
  EXPECT_EQ(cv[0].fields, 5);
  EXPECT_EQ(cv[0].address, "");
  const auto isr = events(all, "interrupt");
  ASSERT_EQ(isr.size(), 1u);
  EXPECT_EQ(isr[0].time, "0.054347827");
  EXPECT_EQ(isr[0].source, "HSC0I");
  // The event row comes before the scan (55 ms) that shows its effect.
  const size_t at_event = text.find("0.054347827,,,cv=pv"), at_scan = text.find("0.055000,motor,0\n");
  ASSERT_NE(at_scan, std::string::npos) << text;
  EXPECT_LT(at_event, at_scan);
  for (const auto& x : all)
    if (x.event.empty()) EXPECT_EQ(x.fields, 3) << x.time << " " << x.address;  // scan rows as before
}

// Cutting (ExampleFiles.Cutting): four HSC0I interrupts at 250, 500, 750, 1000 ms.
TEST(SimTrace, CuttingInterruptsEveryQuarterSecond) {
  const std::string csv = ::testing::TempDir() + "/sim_trace_cut.csv";
  ASSERT_EQ(tool("sim --config " + example("hsc", "cutting") + " --duration 1.5s --watch DR4096 --trace " + csv).status, 0);
  const auto isr = events(rows(slurp(csv)), "interrupt");
  ASSERT_EQ(isr.size(), 4u);
  const char* at[] = {"0.250000000", "0.500000000", "0.750000000", "1.000000000"};
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(isr[k].time, at[k]);
    EXPECT_EQ(isr[k].source, "HSC0I");
  }
}

// Homing example D (Homing.Md2CountsTenPg0PulsesFromTheDogAndLoadsP16): seek at 5 kHz
// from the scan at 0, DOG at -3000 after t1, creep to the 10th PG0 edge at -4996
// after t2, CLR 20 ms, then the step ends.
TEST(SimTrace, HomingPhasesAndStepEndAtTheClosedFormInstants) {
  const std::string csv = ::testing::TempDir() + "/sim_trace_home.csv";
  ASSERT_EQ(tool("sim --config " + example("motion", "homing") + " --duration 3s --watch DR4088 --trace " + csv).status,
            0);
  const auto all = rows(slurp(csv));
  const auto home = events(all, "homing");
  ASSERT_EQ(home.size(), 3u);
  EXPECT_EQ(home[0].source, "PSO0 seek");
  EXPECT_EQ(home[1].source, "PSO0 creep");
  EXPECT_EQ(home[2].source, "PSO0 home");
  const double kA = 460000.0 / 0.1, kF0 = 141;
  const double ta = (5000 - kF0) / kA, sa = (5000.0 * 5000 - kF0 * kF0) / (2 * kA);
  const double t1 = ta + (3000 - sa) / 5000;
  const double td = 4000 / kA, sd = (5000.0 * 5000 - 1000.0 * 1000) / (2 * kA);
  const double t2 = td + (1996 - sd) / 1000;
  EXPECT_NEAR(std::stod(home[0].time), 0.0, 1e-9);
  EXPECT_NEAR(std::stod(home[1].time), t1, 2e-9);
  EXPECT_NEAR(std::stod(home[2].time), t1 + t2, 2e-9);
  const auto step = events(all, "step_end");
  ASSERT_EQ(step.size(), 1u);
  EXPECT_EQ(step[0].source, "PSO0 step 1");
  EXPECT_NEAR(std::stod(step[0].time), t1 + t2 + 0.020, 2e-9);
  // PSO0I is not in this program: no interrupt row.
  EXPECT_TRUE(events(all, "interrupt").empty());
}

// A step end between scans: positioning example A's first step, +10000 Ut at 5000.
TEST(SimTrace, StepEndsAreRowsWithTheirAxisAndStep) {
  const std::string csv = ::testing::TempDir() + "/sim_trace_pos.csv";
  ASSERT_EQ(tool("sim --config " + example("motion", "positioning") + " --duration 10s --watch R4064 --trace " + csv).status,
            0);
  const auto all = rows(slurp(csv));
  const auto steps = events(all, "step_end");
  ASSERT_GE(steps.size(), 4u);
  EXPECT_EQ(steps[0].source, "PSO0 step 1");
  EXPECT_EQ(steps[1].source, "PSO0 step 2");
  // The scan row of R4064 = 1 comes at the first scan at or after the step's instant.
  for (const auto& x : all)
    if (x.address == "R4064" && x.value == "1") {
      EXPECT_GE(std::stod(x.time) + 1e-12, std::stod(steps[0].time));
      EXPECT_LT(std::stod(x.time) - std::stod(steps[0].time), 0.001 + 1e-9);
      break;
    }
}

// ---- --watch formats -------------------------------------------------------------

std::string program() {
  const std::string il = ::testing::TempDir() + "/sim_format.il";
  std::ofstream(il) << "ORG M1925\nOUT M0\nEND\n";
  return il;
}

TEST(SimFormat, SixteenBitRegistersAreSignedByDefault) {
  const Result r = tool("sim --program " + program() +
                        " --duration 2ms --set R1=-500 --set R2=65036 --set D0=32767 --set R3=0x8000 "
                        "--watch R1,R2,D0,R3");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("R1 = -500\nR2 = -500\nD0 = 32767\nR3 = -32768\n"), std::string::npos) << r.out;
}

TEST(SimFormat, SuffixesUnsignedHexAnd32BitSignedAndFloat) {
  // DR10 = 0x40490FDB is the float 3.14159274; DR20 = -100000; WX0 a bit group (X1 on).
  const Result r = tool("sim --program " + program() +
                        " --duration 2ms --set R1=-500 --set DR10=0x40490FDB --set DR20=-100000 --set X1=1 "
                        "--watch R1:u,R1:hex,R1:s,DR10:f32,DR10:hex,DR20,DR20:u,WX0,WX0:hex,M0,M0:hex");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("R1:u = 65036\nR1:hex = 0xFE0C\nR1:s = -500\nDR10:f32 = 3.14159274\nDR10:hex = 0x40490FDB\n"
                       "DR20 = -100000\nDR20:u = 4294867296\nWX0 = 2\nWX0:hex = 0x0002\nM0 = 1\nM0:hex = 0x1\n"),
            std::string::npos)
      << r.out;
}

TEST(SimFormat, TraceRowsUseTheFormat) {
  const std::string csv = ::testing::TempDir() + "/sim_trace_fmt.csv";
  const Result r = tool("sim --program " + program() + " --duration 2ms --set R1=-500 --watch R1,R1:hex --trace " + csv);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(slurp(csv), "time_s,address,value,event,source\n0.000000,R1,-500\n0.000000,R1:hex,0xFE0C\n");
}

TEST(SimFormat, BadFormatsAreUsageErrors) {
  struct Case {
    const char* watch;
    const char* says;
  };
  for (const Case c : {Case{"R1:f32", "f32 needs a 32-bit address"}, Case{"R1:oct", "unknown format 'oct'"},
                       Case{"M0:s", "a single bit has no sign"}}) {
    const Result r = tool("sim --program " + program() + " --duration 2ms --watch " + c.watch);
    EXPECT_NE(r.status, 0) << c.watch;
    EXPECT_NE(r.out.find(c.says), std::string::npos) << c.watch << "\n" << r.out;
  }
}

}  // namespace
