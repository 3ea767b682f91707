// FUN30 PID against values worked out by hand, and a closed loop in virtual time.
#include <gtest/gtest.h>

#include <cmath>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/temp/pid.h"
#include "plc_cell/temp/thermal_plant.h"

namespace plc_cell {
namespace temp {
namespace {

FunctionTable table() {
  FunctionTable t = FunctionTable::with_core_functions();
  add_pid_function(t);
  return t;
}

// A/M = M0, BUM = M1, D/R = M2; Ts in R10; SR R100.., OR R200, PR R300.., WR R400..
const char* kProgram =
    "ORG M0\nLD M1\nLD M2\n"
    "FUN 30 Ts=R10 SR=R100 OR=R200 PR=R300 WR=R400 ERR=M100 HAL=M101 LAL=M102\nEND\n";

class Fun30 : public ::testing::Test {
 protected:
  Fun30() : p(table()) {
    p.load_program_text(kProgram, "pid.il");
    EXPECT_TRUE(p.set_mode(RunMode::Run));
    // 0..1000 engineering over 0..16380 raw; SP 500, HAL 900, LAL 100.
    w("R100", {0, 500, 900, 100, 1000, 0, 0, 0});
    w("R300", {1000, 0, 0, 0, 16383, 0, 0});  // Pb 100 %: Kc = 1000/1000 = 1
    w("R10", {100});                          // Ts 1.00 s
    w("M2", {1});                             // direct
  }
  void w(const char* a, std::vector<uint32_t> v) { p.write(parse_address(a), v); }
  uint32_t r(const char* a) { return p.read(parse_address(a), 1)[0]; }
  int32_t sr(const char* a) { return int16_t(r(a)); }
  Plc p;
};

TEST_F(Fun30, ProportionalOnTheRawScale) {
  w("R106", {4095});  // PV 250.0 of 1000
  w("M0", {1});
  p.scan(0);
  EXPECT_EQ(r("M100"), 0u);
  EXPECT_EQ(sr("R100"), 250);  // scaled PV
  // E = (8190 - 4095) x 16383/16380 = 4095.75 counts, Kc 1.
  EXPECT_EQ(r("R200"), 4096u);
  EXPECT_TRUE(r("R400") & 0x3u);  // auto, solved this scan
  EXPECT_EQ(r("R404"), 4095u);    // PV of this solve
  // Reverse action: the output falls as the error rises (clamped at 0).
  w("M2", {0});
  p.scan(1000000);
  EXPECT_EQ(r("R200"), 0u);
}

TEST_F(Fun30, SolutionIntervalFromTheOneMillisecondTimer) {
  w("R106", {4095});
  w("R301", {100});  // Ki 1 repeat/min
  w("M0", {1});
  p.scan(0);  // entering auto: solved at once
  EXPECT_EQ(r("R401"), 0u);
  p.scan(999000);
  EXPECT_FALSE(r("R400") & 0x2u);  // 999 ms < 10 x Ts
  p.scan(1000000);
  EXPECT_TRUE(r("R400") & 0x2u);
  EXPECT_EQ(r("R401"), 1000u);
  // One solve of the integral: Kc E Ki Ts / 600000 = 4095.75 x 100 x 100 / 600000 = 68.26.
  EXPECT_EQ(r("R200"), 4096u + 68u);
  p.scan(1001000);
  EXPECT_FALSE(r("R400") & 0x2u);  // on for one scan only
}

TEST_F(Fun30, AlarmsInManualAndErrors) {
  w("R106", {16000});  // PV 976.8 >= HAL 900
  p.scan(0);           // A/M = 0: manual
  EXPECT_EQ(r("M101"), 1u);
  EXPECT_EQ(r("M102"), 0u);
  EXPECT_EQ(r("R200"), 0u);  // manual: the program owns OR
  w("R106", {1000});   // 61.1 <= LAL 100
  p.scan(1000);
  EXPECT_EQ(r("M102"), 1u);
  w("R300", {0});      // Pb 0 is out of range
  p.scan(2000);
  EXPECT_EQ(r("M100"), 1u);
  EXPECT_TRUE(r("R400") & 0x10u);
  // 4-20 mA on a 0-20 mA range: OPV 3276, RAM 3276 reads LER.
  w("R300", {1000});
  w("R107", {3276});
  w("R106", {3276});
  p.scan(3000);
  EXPECT_EQ(r("M100"), 0u);
  EXPECT_EQ(sr("R100"), 0);
}

TEST_F(Fun30, BumplessTransferKeepsTheManualOutput) {
  w("R106", {8190});  // at SP: P = 0
  w("R301", {50});
  w("M1", {1});       // BUM
  p.scan(0);          // manual
  w("R200", {7000});  // the operator's output
  p.scan(1000);
  w("M0", {1});       // to auto
  p.scan(2000);
  EXPECT_EQ(r("R200"), 7000u);
  // Without BUM the integral starts from 0: the output jumps to P + bias = 0.
  w("M0", {0});
  w("M1", {0});
  p.scan(3000);
  w("M0", {1});
  p.scan(4000);
  EXPECT_EQ(r("R200"), 0u);
}

// FUN30 on a heater driven through an analog output (OR -> a DA -> an SCR): the test
// plays the AI module, loading the plant's temperature into SR+6 each scan.
TEST_F(Fun30, HoldsAPlantOnAnAnalogHeater) {
  ThermalPlantParams q;
  q.ambient_c = 20, q.initial_c = 20, q.gain_c = 400, q.tau_s = 300, q.dead_time_s = 5;
  ThermalPlant plant(q);
  w("R101", {150});  // SP 150 of 0..1000 degC
  w("R300", {80, 60, 0, 0, 16383, 0, 0});  // Pb 8 % (Kc 12.5), Ki 0.6 repeats/min
  w("R10", {50});    // Ts 0.5 s
  w("M0", {1});
  double worst = 0;
  for (uint64_t t = 0; t < 3600ull * 1000000; t += 10000) {
    p.write(parse_address("R106"), {uint32_t(std::lround(plant.temperature_c() * 16.38))});
    p.scan(t);
    plant.step(10000, r("R200") / 16383.0);
    if (t > 1800ull * 1000000) worst = std::max(worst, std::fabs(plant.temperature_c() - 150));
  }
  EXPECT_EQ(r("M100"), 0u);
  EXPECT_LT(worst, 1.0);
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
