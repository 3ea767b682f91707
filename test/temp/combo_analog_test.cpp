// The AI part of the FBs-2A4TC / 2A4RTD (manual A:7206-A:7370): two channels with the
// AI modules' jumpers and formats, in the analog IR chain; the temperature part stays in
// modules.temperature.
#include <gtest/gtest.h>

#include "config_error.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace temp {
namespace {

const char* kCell = R"(
modules:
  temperature:
    first_ir: 10                 # the temperature part's 2 IR: R3850, R3851
    modules:
      - {type: 2A4TC, sensor: K, channels: [{temperature: 25}]}
      - {type: 2A4RTD, sensor: PT100, channels: [{temperature: 25}]}
  analog:
    modules:
      - type: 6AD                # CH0-CH5: R3840-R3845
      - type: 2A4TC              # its AI: CH6, CH7 = R3846, R3847 (JP1 bipolar code, +-10 V)
        inputs: [{value: 0}, {value: 10}]
      - type: 2A4RTD             # CH8, CH9 = R3848, R3849: unipolar code, 0-20 mA on CH9
        code: unipolar
        signal: unipolar
        inputs: [{value: 5}, {current: true, value: 10}]
)";

TEST(ComboAnalog, TwoAiChannelsInTheIrChain) {
  Plc plc(FunctionTable::with_core_functions());
  std::unique_ptr<TemperatureCell> cell;
  plc.locked([&](ScanEngine& e, Memory& m) {
    cell = make_temperature_cell(YAML::Load(kCell), "c.yaml", m);
    e.add_hook(cell.get());
    return 0;
  });
  plc.load_program_text("ORG M0\nINC R0\nEND\n", "p.il");
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  plc.scan(0);
  auto ir = [&](uint32_t n) { return int16_t(plc.read(Address{Area::R, Width::Word, 3840 + n}, 1)[0]); };
  // The manual's codes (A:5969): +-10 V signal, bipolar code: 0 V -> 0, +10 V -> 8191;
  // the default format is 14-bit with valid 12 bits (B1 = B0 = 0): 8191 -> 8188.
  EXPECT_EQ(ir(6), 0);
  EXPECT_EQ(ir(7), 8188);
  // Unipolar 0-10 V, unipolar code: 5 V -> 8191.5 -> 8192 (valid 12: 8192); 10 mA of 20 -> 8192.
  EXPECT_EQ(ir(8), 8192);
  EXPECT_EQ(ir(9), 8192);
  plc.locked([&](ScanEngine& e, Memory&) {
    e.remove_hook(cell.get());
    return 0;
  });
}

TEST(ComboAnalog, AiPartNeedsItsTemperatureModule) {
  const std::string e = config_error("modules:\n  analog:\n    modules:\n      - {type: 2A4RTD}\n");
  EXPECT_NE(e.find("1 2A4RTD analog part(s) but 0 2A4RTD in modules.temperature"), std::string::npos) << e;
  EXPECT_NE(config_error("modules:\n  analog:\n    modules:\n      - {type: 2A4TC, inputs: [{}, {}, {}]}\n")
                .find("a list of at most 2 inputs for a 2A4TC"),
            std::string::npos);
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
