// FBs-B4AD / B2DA / B2A1D expansion boards: D4072-D4077 (manual A:6573-A:6750).
#include <gtest/gtest.h>

#include "config_error.h"

#include "plc_cell/core/error.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace temp {
namespace {

TEST(AnalogBoard, Codes) {
  EXPECT_EQ(board_input_code(0, false), 0);
  EXPECT_EQ(board_input_code(10, false), 16380);  // "0 ~ 16380"
  EXPECT_EQ(board_input_code(20, true), 16380);
  EXPECT_EQ(board_input_code(5, false), 8192);    // 2047.5 -> 2048 steps of 4
  EXPECT_EQ(board_input_code(0.00244, false), 4);  // the finest step: 2.44 mV
  EXPECT_EQ(board_input_code(12, false), 16380);  // saturates
  EXPECT_EQ(board_input_code(-1, false), 0);
  EXPECT_EQ(board_input_code(0.00488, true), 4);   // 4.88 uA
  EXPECT_DOUBLE_EQ(board_output_signal(16380, false), 10.0);
  EXPECT_DOUBLE_EQ(board_output_signal(16383, true), 20.0);  // clamped to 16380
  EXPECT_DOUBLE_EQ(board_output_signal(-5, false), 0.0);
  EXPECT_DOUBLE_EQ(board_output_signal(8191, false), 2047 / 4095.0 * 10);  // low bits dropped
}

class BoardTest : public ::testing::Test {
 protected:
  void setup(const std::string& yaml, const std::string& program) {
    plc.locked([&](ScanEngine& e, Memory& m) {
      cell = make_temperature_cell(YAML::Load(yaml), "b.yaml", m);
      e.add_hook(cell.get());
      return 0;
    });
    plc.load_program_text(program, "b.il");
    ASSERT_TRUE(plc.set_mode(RunMode::Run));
  }
  void TearDown() override {
    if (cell)
      plc.locked([&](ScanEngine& e, Memory&) {
        e.remove_hook(cell.get());
        return 0;
      });
  }
  uint32_t get(const std::string& a) { return plc.read(parse_address(a), 1).at(0); }
  void put(const std::string& a, uint32_t v) { plc.write(parse_address(a), {v}); }
  void scan() { plc.scan(t), t += 1000; }
  Plc plc;
  std::unique_ptr<TemperatureCell> cell;
  uint64_t t = 0;
};

TEST_F(BoardTest, B4adInputsEveryScan) {
  setup(R"(
modules:
  analog:
    board:
      type: B4AD
      inputs:
        - {name: level, value: 2.5}
        - {name: loop, current: true, value: 12}
        - {name: tx, current: true, plant: tank, plant_range: [0, 100], offset: true}
    modules:
      - {type: 6AD, code: unipolar, signal: unipolar, inputs: [{value: 10}]}
  plants:
    - {name: tank, ambient: 25, initial: 25}
)", "ORG M1925\nOUT M0\nEND\n");
  scan();
  EXPECT_EQ(get("D4072"), 4096u);   // 2.5 V: 1023.75 -> 1024 steps
  EXPECT_EQ(get("D4073"), 9828u);   // 12 mA: 2457 steps
  EXPECT_EQ(get("D4074"), 6552u);   // 25 degC on a 0-100 degC 4-20 mA transmitter: 8 mA, 1638 steps
  EXPECT_EQ(get("D4075"), 0u);      // unwired: 0 V
  EXPECT_EQ(get("R3840"), 16380u);  // the IR modules are unaffected (valid 12 in 14-bit format)
}

TEST_F(BoardTest, B2a1dOutputAndWatchdog) {
  setup(R"(
modules:
  analog:
    board:
      type: B2A1D
      inputs: [{value: 10}, {value: 5}]
      outputs: [{name: valve, current: true}]
)", "ORG M1925\nMOV S=D4072 D=D4076\nEND\n");
  scan();
  scan();
  const auto& out = cell->analog()->outputs();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(get("D4072"), 16380u);
  EXPECT_EQ(get("D4073"), 8192u);
  EXPECT_DOUBLE_EQ(out[0].signal, 20.0);  // the full input code sent to the 0-20 mA output
  EXPECT_EQ(get("D4074"), 0u);            // a B2A1D has two inputs only
  plc.set_mode(RunMode::Stop);
  for (int k = 0; k < 500; ++k) scan();
  EXPECT_EQ(out[0].signal, 0.0);  // not serviced for 0.5 s
  EXPECT_TRUE(out[0].watchdog);
}

TEST(AnalogBoardConfig, Errors) {
  const auto bad = config_error;
  EXPECT_NE(bad("modules: {analog: {board: {type: B8AD}}}").find("B4AD"), std::string::npos);
  EXPECT_NE(bad("modules: {analog: {board: {type: B2DA, inputs: [{value: 1}]}}}").find("at most 0"), std::string::npos);
  EXPECT_NE(bad("modules: {analog: {board: {type: B2A1D, outputs: [{}, {}]}}}").find("at most 1"), std::string::npos);
  EXPECT_NE(bad("modules: {analog: {board: {type: B4AD, inputs: [{plant: x}]}}}").find("unknown plant"),
            std::string::npos);
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
