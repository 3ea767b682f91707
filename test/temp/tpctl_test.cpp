// FUN86 TPCTL: the math of one point, the instruction's registers, and an oven
// brought from 25 to 200 degC in virtual time.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/temp/temperature_cell.h"
#include "plc_cell/temp/tpctl.h"

namespace plc_cell {
namespace temp {
namespace {

TEST(TpctlPoint, ProportionalBandOfTheDefaultGain) {
  // Kc 110: full output 14.9 degC below SP (manual A:7129: Pb 0.91 % of 1638 degC).
  TpctlPoint p;
  EXPECT_EQ(p.solve(2000, 2000 - 149, 110, 0, 0, 40, true, 1), kTpctlFullScale);
  TpctlPoint q;
  EXPECT_NEAR(q.solve(2000, 1950, 110, 0, 0, 40, true, 1), 5500, 1e-9);
  TpctlPoint cool;  // cooling: output rises with PV above SP
  EXPECT_NEAR(cool.solve(2000, 2050, 110, 0, 0, 40, false, 1), 5500, 1e-9);
}

TEST(TpctlPoint, IntegralAndDerivativeUnits) {
  // Ki 100 = 1 repeat/min: over 60 s of solves at Ts 4 s the integral adds one P term.
  TpctlPoint p;
  double out = 0;
  for (int k = 0; k < 15; ++k) out = p.solve(1000, 990, 100, 100, 0, 40, true, 1);
  EXPECT_NEAR(out, 1000 + 1000, 1e-6);
  // Td 100 = 1 min: a PV rising 1 (0.1 degC) per 4 s solve removes Kc x 60 s x 0.025/s = 1.5 Kc.
  TpctlPoint d;
  d.solve(1000, 900, 100, 0, 100, 40, true, 1);
  EXPECT_NEAR(d.solve(1000, 901, 100, 0, 100, 40, true, 1), 100 * 99 - 100 * 6.0 * 100 * 1 / 40, 1e-9);
}

TEST(TpctlPoint, AntiWindupAndMinimumOvershootMethod) {
  TpctlPoint p;
  for (int k = 0; k < 1000; ++k) p.solve(2000, 250, 110, 50, 0, 40, true, 1);  // saturated high
  EXPECT_LE(p.integral, 0.0);  // the integral did not wind up (it starts at 0 and never grows)
  TpctlPoint m;
  for (int k = 0; k < 1000; ++k) m.solve(2000, 1000, 110, 50, 0, 40, true, 0);  // outside the band
  EXPECT_EQ(m.integral, 0.0);
  m.solve(2000, 1990, 110, 50, 0, 40, true, 0);  // inside: integrates
  EXPECT_GT(m.integral, 0.0);
}

FunctionTable table() {
  FunctionTable t = FunctionTable::with_core_functions();
  add_tpctl_function(t);
  return t;
}

const char* kProgram =
    "ORG M1924\n"
    "MOV S=2000 D=R100\n"   // SV 200.0
    "MOV S=10 D=R110\n"     // in-zone +-1.0
    "MOV S=80 D=R120\n"     // Kc: full output 20.5 degC below SP
    "MOV S=40 D=R130\n"     // Ki 0.4 repeats/min (reset 2.5 min)
    "MOV S=20 D=R140\n"     // Td 0.2 min
    "ORG M0\n"
    "LD M1925\n"            // H/C = 1: heating
    "FUN 86 Md=0 Yn=Y0 Sn=0 Zn=1 Sv=R100 Os=R110 PR=R120 IR=R130 DR=R140 OR=R200 WR=R300 ERR=M100 ALM=M101\n"
    "END\n";

const char* kOven = R"(
modules:
  temperature:
    modules:
      - type: 2TC
        sensor: K
        channels: [{name: oven, plant: oven}]
  plants:
    - {name: oven, ambient: 25, initial: 25, gain: 300, time_constant: 600, dead_time: 10, heater: Y0}
)";

TEST(Fun86Registration, OperandsAndErrors) {
  FunctionTable t = FunctionTable::with_core_functions();
  add_tpctl_function(t);
  ASSERT_NE(t.find("TPCTL"), nullptr);
  EXPECT_EQ(t.find(86)->operands.size(), 13u);
}

TEST(Fun86, ErrWithoutTemperatureSourceOrBadRange) {
  Plc p(table());
  p.load_program_text("ORG M0\nLD M1925\nFUN 86 Md=0 Yn=Y0 Sn=30 Zn=3 Sv=R100 Os=R110 PR=R120 IR=R130 "
                      "DR=R140 OR=R200 WR=R300 ERR=M100 ALM=M101\nEND\n", "t.il");
  ASSERT_TRUE(p.set_mode(RunMode::Run));
  p.write(parse_address("M0"), {1});
  p.scan(0);
  EXPECT_EQ(p.read(parse_address("M100"), 1)[0], 1u);  // Sn + Zn > 32
}

TEST(Fun86, PvFromR4004WithoutModules) {
  Plc p(table());
  p.load_program_text("ORG M0\nLD M1925\nFUN 86 Md=1 Yn=Y0 Sn=0 Zn=2 Sv=R100 Os=R110 PR=R120 IR=R130 "
                      "DR=R140 OR=R200 WR=R300 ERR=M100 ALM=M101\nEND\n", "t.il");
  ASSERT_TRUE(p.set_mode(RunMode::Run));
  p.write(parse_address("R4003"), {0xA55A});
  p.write(parse_address("R4004"), {20500});  // PVs at D500
  p.write(parse_address("R4012"), {0xFFFF});
  p.write(parse_address("R4005"), {0x0102});
  p.write(parse_address("R4008"), {3500});
  p.write(parse_address("D500"), {1950, 2100});
  p.write(parse_address("R100"), {2000, 2000});
  p.write(parse_address("R110"), {50, 50});
  p.write(parse_address("M0"), {1});
  p.scan(0);
  EXPECT_EQ(p.read(parse_address("M100"), 1)[0], 0u);
  EXPECT_EQ(p.read(parse_address("R120"), 2), (std::vector<uint32_t>{110, 110}));  // defaults
  EXPECT_EQ(p.read(parse_address("R130"), 2), (std::vector<uint32_t>{17, 17}));
  EXPECT_EQ(p.read(parse_address("R140"), 2), (std::vector<uint32_t>{50, 50}));
  EXPECT_EQ(p.read(parse_address("R300"), 1)[0], 1u);  // point 0 in zone 1950..2050, point 1 not
  EXPECT_EQ(p.read(parse_address("M101"), 1)[0], 1u);  // ALM: point 1 out of zone
  // P = 110 x 50 = 5500, plus the first integral step 110 x 50 x 17 x 40 / 60000 = 62.3.
  EXPECT_EQ(p.read(parse_address("R200"), 1)[0], 5562u);
  EXPECT_EQ(p.read(parse_address("R201"), 1)[0], 0u);
  EXPECT_EQ(p.read(parse_address("Y0"), 2), (std::vector<uint32_t>{1, 0}));
  // PWM: 2 s cycle, duty 5562/16383 = 0.339498 -> on for 678.996 ms.
  p.scan(678000);
  EXPECT_EQ(p.read(parse_address("Y0"), 1)[0], 1u);
  p.scan(679000);
  EXPECT_EQ(p.read(parse_address("Y0"), 1)[0], 0u);
  // High temperature: PV >= R4008 on ten successive executions.
  p.write(parse_address("R4008"), {2000});
  for (int k = 0; k < 9; ++k) p.scan(700000 + k * 1000);
  EXPECT_EQ(p.read(parse_address("R302"), 1)[0], 0u);
  p.scan(800000);
  EXPECT_EQ(p.read(parse_address("R302"), 1)[0], 2u);  // point 1 (PV 210.0) warns
  // Disabled point: output off. EN off: all off.
  p.write(parse_address("R4012"), {0xFFFE});
  p.scan(900000);
  EXPECT_EQ(p.read(parse_address("Y0"), 1)[0], 0u);
  p.write(parse_address("M0"), {0});
  p.scan(901000);
  EXPECT_EQ(p.read(parse_address("Y0"), 2), (std::vector<uint32_t>{0, 0}));
}

TEST(Fun86, StopAndRunStartsAfresh) {
  Plc p(table());
  p.load_program_text("ORG M1925\nLD M1925\nFUN 86 Md=1 Yn=Y0 Sn=0 Zn=1 Sv=R100 Os=R110 PR=R120 IR=R130 "
                      "DR=R140 OR=R200 WR=R300\nEND\n", "t.il");
  auto setup = [&] {
    p.write(parse_address("R4003"), {0xA55A});
    p.write(parse_address("R4004"), {20500});
    p.write(parse_address("R4012"), {0xFFFF});
    p.write(parse_address("R4005"), {0x0102});  // Ts 4 s
    p.write(parse_address("D500"), {1000});
    p.write(parse_address("R100"), {2000});
    p.write(parse_address("R120"), {10});
    p.write(parse_address("R130"), {0});
  };
  ASSERT_TRUE(p.set_mode(RunMode::Run));
  setup();
  p.scan(0);
  p.scan(1000);
  // P 10 x 1000 plus one integral step with the default Ki 17: 10 x 1000 x 17 x 40 / 60000 = 113.
  EXPECT_EQ(p.read(parse_address("R200"), 1)[0], 10113u);
  p.set_mode(RunMode::Stop);
  ASSERT_TRUE(p.set_mode(RunMode::Run));
  setup();
  p.write(parse_address("D500"), {1500});
  p.scan(2000);  // first scan of the new RUN: solves at once instead of waiting for t = 4 s
  p.scan(3000);
  // 5000 + 57 with a fresh integral (the old one would give 5170).
  EXPECT_EQ(p.read(parse_address("R200"), 1)[0], 5057u);
}

// The acceptance test: the oven from 25 degC to 200 degC under FUN86, then held
// within +-1 degC. Writes the trace for docs/oven.png when PLC_CELL_OVEN_TRACE is set.
TEST(Fun86Oven, ReachesAndHolds200) {
  Plc p(table());
  std::unique_ptr<TemperatureCell> cell;
  p.locked([&](ScanEngine& e, Memory& m) {
    cell = make_temperature_cell(YAML::Load(kOven), "oven.yaml", m);
    e.add_hook(cell.get());
    return 0;
  });
  p.load_program_text(kProgram, "oven.il");
  ASSERT_TRUE(p.set_mode(RunMode::Run));
  p.write(parse_address("M0"), {1});
  const char* trace_path = std::getenv("PLC_CELL_OVEN_TRACE");
  std::ofstream trace;
  if (trace_path) trace.open(trace_path), trace << "t_s,plant_c,reading_c,output\n";
  const uint64_t scan = 10000;  // 10 ms scans keep the hour of virtual time quick
  double reached = -1, worst = 0, peak = 0;
  for (uint64_t t = 0; t <= 3600ull * 1000000; t += scan) {
    p.scan(t);
    const double temp = cell->plant("oven")->temperature_c();
    peak = std::max(peak, temp);
    if (reached < 0 && temp >= 199.9) reached = t / 1e6;
    if (reached >= 0) worst = std::max(worst, std::fabs(temp - 200.0));
    if (trace.is_open() && t % 1000000 == 0)
      trace << t / 1e6 << "," << temp << "," << int16_t(p.read(parse_address("R0"), 1)[0]) / 10.0 << ","
            << p.read(parse_address("R200"), 1)[0] << "\n";
  }
  EXPECT_EQ(p.read(parse_address("M100"), 1)[0], 0u);
  ASSERT_GT(reached, 0) << "never reached 200 degC; peak " << peak;
  EXPECT_LT(reached, 1200);
  EXPECT_LE(worst, 1.0) << "reached at " << reached << " s, peak " << peak;
  EXPECT_EQ(p.read(parse_address("R300"), 1)[0] & 1u, 1u);  // in zone at the end
  EXPECT_EQ(p.read(parse_address("M101"), 1)[0], 0u);
  std::printf("oven: 200 degC at %.0f s, peak %.2f degC, worst deviation after %.2f degC\n", reached, peak, worst);
  p.locked([&](ScanEngine& e, Memory&) {
    e.remove_hook(cell.get());
    return 0;
  });
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
