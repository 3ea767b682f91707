// Analog I/O modules in PLC memory: IR/OR allocation, formats, averaging, watchdog.
#include <gtest/gtest.h>

#include "config_error.h"

#include "plc_cell/core/error.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace temp {
namespace {

const char* kCell = R"(
modules:
  analog:
    first_ir: 1
    modules:
      - type: 6AD                    # IR R3841..R3846, bipolar code, +-10 V
        inputs:
          - {name: zero, value: 0}
          - {name: full, value: 10}
          - {name: neg, value: -10}
          - {name: loop, current: true, value: 12}   # +-20 mA: 12 mA
      - type: 4A2D                   # IR R3847..R3850, OR R3904..R3905
        code: unipolar
        signal: unipolar
        inputs:
          - {name: oven_tx, current: true, plant: oven, plant_range: [0, 500], offset: true}
        outputs:
          - {name: valve}
          - {name: pump, current: true}
  plants:
    - {name: oven, ambient: 125, initial: 125}
)";

class AnalogTest : public ::testing::Test {
 protected:
  void SetUp() override {
    plc.locked([&](ScanEngine& e, Memory& m) {
      cell = make_temperature_cell(YAML::Load(kCell), "a.yaml", m);
      e.add_hook(cell.get());
      return 0;
    });
    plc.load_program_text("ORG M1925\nMOV S=R0 D=R3904\nMOV S=R1 D=R3905\nEND\n", "a.il");
    ASSERT_TRUE(plc.set_mode(RunMode::Run));
  }
  void TearDown() override {
    plc.locked([&](ScanEngine& e, Memory&) {
      e.remove_hook(cell.get());
      return 0;
    });
  }
  int32_t ir(uint32_t n) { return int16_t(plc.read(parse_address("R" + std::to_string(3840 + n)), 1)[0]); }
  void put(const char* a, uint32_t v) { plc.write(parse_address(a), {v}); }
  Plc plc;
  std::unique_ptr<TemperatureCell> cell;
  uint64_t t = 0;
  void scan() { plc.scan(t), t += 1000; }
};

TEST_F(AnalogTest, DefaultFormatIsFourteenBitWithValidTwelve) {
  scan();
  EXPECT_EQ(ir(0), 0);     // IR before first_ir untouched
  EXPECT_EQ(ir(1), 0);     // 0 V, bipolar code
  EXPECT_EQ(ir(2), 8188);  // +10 V: 8191 with B1 = B0 = 0
  EXPECT_EQ(ir(3), -8192);
  EXPECT_EQ(ir(4), 4912);  // 12 mA of +-20 mA: 16383 x 32/40 - 8192 = 4914.4 -> 4914 -> 4912
  // 4-20 mA transmitter on a 0..500 degC span, oven at 125 degC: 8 mA of 0..20 mA.
  EXPECT_EQ(ir(7), 6552);  // 16383 x 8/20 = 6553.2 -> 6553 -> 6552
  EXPECT_EQ(offset_4_20(ir(7), false), 4095);  // the ladder's 4-20 mA value: a quarter scale
}

TEST_F(AnalogTest, ValidFourteenBitsAndTwelveBitFormat) {
  put("D4006", 0x0004);  // CH2 valid 14-bit
  put("D4011", 0x0100);  // CH3 averaging 1 (CH2 left 0: illegal -> 8 for valid-14)
  scan();
  EXPECT_EQ(ir(2), 8191);
  EXPECT_EQ(ir(3), -8192);
  put("D4042", 0x5612);  // all 12-bit
  scan();
  EXPECT_EQ(ir(2), 2047);
  EXPECT_EQ(ir(3), -2048);
}

TEST(AnalogAveraging, MovingAverageFollowsAStep) {
  // A transmitter on a plant that jumps from 125 to 375 degC within the first 2 s step
  // (tau 0.1 s): 8 mA -> 16 mA on 0..20 mA, i.e. 6553 -> 13106 (valid 14-bit).
  const char* yaml = R"(
modules:
  analog:
    modules:
      - type: 6AD
        code: unipolar
        signal: unipolar
        inputs:
          - {current: true, plant: p, plant_range: [0, 500], offset: true}
  plants:
    - {name: p, ambient: 375, initial: 125, gain: 0, time_constant: 0.1, dead_time: 0}
)";
  Plc plc;
  std::unique_ptr<TemperatureCell> cell;
  plc.locked([&](ScanEngine& e, Memory& m) {
    cell = make_temperature_cell(YAML::Load(yaml), "a.yaml", m);
    e.add_hook(cell.get());
    return 0;
  });
  plc.load_program_text("ORG M1924\nMOV S=1 D=D4006\nMOV S=4 D=D4010\nEND\n", "a.il");
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  auto ir0 = [&] { return int16_t(plc.read(parse_address("R3840"), 1)[0]); };
  // The first scan samples before the program sets D4006/D4010: valid-12 and no averaging.
  plc.scan(0);
  EXPECT_EQ(ir0(), 6552);
  const int expected[] = {9830, 10922, 11468, 13106};  // means of 2, 3, 4 samples, then steady
  for (int k = 0; k < 4; ++k) {
    plc.scan(2000000ull * (k + 1));
    if (k == 3) plc.scan(2000000ull * 5);
    EXPECT_EQ(ir0(), expected[k]) << k;
  }
  plc.locked([&](ScanEngine& e, Memory&) {
    e.remove_hook(cell.get());
    return 0;
  });
}

TEST_F(AnalogTest, OutputsAndWatchdog) {
  put("R0", 8191);   // valve: +-10 V? no: this module is unipolar code, 0..10 V
  put("R1", 16383);  // pump: 20 mA
  scan();
  const auto& out = cell->analog()->outputs();
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].or_index, 0u);
  EXPECT_NEAR(out[0].signal, 10.0 * 8191 / 16383, 1e-9);
  EXPECT_NEAR(out[1].signal, 20.0, 1e-9);
  EXPECT_FALSE(out[0].watchdog);
  // STOP: the CPU no longer services the module; 0.5 s later the outputs drop to 0.
  plc.set_mode(RunMode::Stop);
  for (int k = 0; k < 499; ++k) scan();
  EXPECT_NEAR(out[1].signal, 20.0, 1e-9);
  scan();
  EXPECT_EQ(out[1].signal, 0.0);
  EXPECT_TRUE(out[1].watchdog);
}

TEST(AnalogConfig, Errors) {
  const auto bad = config_error;
  EXPECT_NE(bad("modules: {analog: {modules: [{type: 8AD}]}}").find("6AD"), std::string::npos);
  EXPECT_NE(bad("modules: {analog: {modules: [{type: 2DA, inputs: [{value: 1}]}]}}").find("at most 0"),
            std::string::npos);
  EXPECT_NE(bad("modules: {analog: {modules: [{type: 6AD, inputs: [{plant: x}]}]}}").find("unknown plant"),
            std::string::npos);
  EXPECT_NE(bad("modules: {analog: {first_ir: 60, modules: [{type: 6AD}]}}").find("64"), std::string::npos);
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
