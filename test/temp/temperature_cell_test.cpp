// Temperature modules in PLC memory, in virtual time.
#include <gtest/gtest.h>

#include "config_error.h"

#include <cmath>

#include "../core/plc_fixture.h"
#include "plc_cell/core/error.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace temp {
namespace {

class TemperatureCellTest : public PlcFixture {
 protected:
  void setup(const std::string& yaml, const std::string& program = "ORG M1925\nOUT M0\nEND\n") {
    const YAML::Node doc = YAML::Load(yaml);
    plc.locked([&](ScanEngine& e, Memory& m) {
      cell = make_temperature_cell(doc, "cell.yaml", m);
      e.add_hook(cell.get());
      return 0;
    });
    load(program);
  }
  void TearDown() override {
    plc.locked([&](ScanEngine& e, Memory&) {
      e.remove_hook(cell.get());
      return 0;
    });
  }
  std::unique_ptr<TemperatureCell> cell;
};

const char* kTwoModules = R"(
modules:
  temperature:
    readings: R0
    working: D0
    table: R5000
    first_ir: 2
    modules:
      - type: 6TC
        sensor: K
        cold_junction: 30
        channels:
          - {name: a, temperature: 123.44}
          - {name: b, temperature: -50.06}
          - {name: hot, temperature: 1400}
          - {name: broken, open: true}
      - type: 6RTD
        sensor: PT100
        channels:
          - {name: c, temperature: 0}
          - {name: d, temperature: 600}
)";

TEST_F(TemperatureCellTest, ReadingsAppearAfterTheMultiplexedScan) {
  setup(kTwoModules);
  // 6TC normal: 4 s for 6 channels, one every 666.666 ms; channel 0 at t = 0.
  scans(1);
  EXPECT_EQ(sget("R0"), 1234);  // 123.44 degC -> 1234 (0.1 degC)
  EXPECT_EQ(sget("R1"), 0);     // not read yet
  EXPECT_EQ(get("D0") >> 8, 0u);  // measurement not complete
  scans(700);                   // t = 0.7 s: channel 1 has been read
  EXPECT_EQ(sget("R1"), -501);
  EXPECT_EQ(sget("D7"), 1);     // WR+7: current channel of module #1
  scans(4000);
  EXPECT_EQ(get("D0"), 0x5600u);  // all read: execute code 56H
  EXPECT_EQ(sget("R2"), 13000);  // 1400 degC is beyond K's 1300: clamped and abnormal
  EXPECT_EQ(sget("R3"), kLineBrokenValue);
  EXPECT_EQ(sget("R4"), kLineBrokenValue);  // unwired inputs read as broken lines
  EXPECT_EQ(sget("R6"), 0);
  EXPECT_EQ(sget("R7"), 6000);
  // Abnormal bits: channels 2, 3, 4, 5 (TC) and 8..11 (unwired RTD inputs).
  EXPECT_EQ(get("D1"), 0x0F3Cu);
  EXPECT_EQ(get("D2"), 0u);
  EXPECT_EQ(get("D3"), (12u << 8) | 2u);  // 12 channels, 2 modules
  EXPECT_EQ(get("D5"), (6u << 8) | 2u);   // module 1: 6 channels, IR 2
  EXPECT_EQ(get("D9"), (6u << 8) | 3u);   // module 2: IR 3
  EXPECT_EQ(get("D10"), 6u);              // module 2's readings start at channel 6
  EXPECT_EQ(get("D8"), (0x10u << 8) | 1u);  // Pt100 DIN, module index 1
  // The configuration table as WinProladder writes it.
  EXPECT_EQ(get("R5000"), 0xA556u);
  EXPECT_EQ(get("R5001"), 2u << 8);
  EXPECT_EQ(get("R5002"), 10000u);  // readings at R0
  EXPECT_EQ(get("R5003"), 20000u);  // working registers at D0
  EXPECT_EQ(get("R5004"), (1u << 8) | 2u);  // K, 6TC
}

TEST_F(TemperatureCellTest, NotInstalledReadsZeroWithoutWarning) {
  setup(kTwoModules);
  scans(4100);
  EXPECT_EQ(get("R4010"), 0xFFFFu);  // the manual's default, set on the first scan
  put("R4010", 0xFFF7);              // point 4 (channel 3, the broken one) not installed
  scans(1);
  EXPECT_EQ(sget("R3"), 0);
  EXPECT_EQ(get("D1") & 0x8u, 0u);
}

TEST_F(TemperatureCellTest, BreakAndMendALine) {
  setup(kTwoModules);
  scans(4100);
  cell->set_open(0, true);
  scans(4000);
  EXPECT_EQ(sget("R0"), kLineBrokenValue);
  EXPECT_TRUE(get("D1") & 1u);
  cell->set_open(0, false);
  scans(4000);
  EXPECT_EQ(sget("R0"), 1234);
  EXPECT_FALSE(get("D1") & 1u);
}

// What a topic publishes is what the registers say: the reading in 0.1 degree, NaN while
// a line is broken or a channel not installed, and degrees Celsius whatever the unit.
TEST_F(TemperatureCellTest, ReadingsDecodeTheRegistersTheProgramSees) {
  setup(kTwoModules);
  scans(4000);
  const auto r = plc.locked([&](ScanEngine&, Memory& m) { return cell->readings(m); });
  ASSERT_EQ(r.size(), 12u);  // 6TC + 6RTD
  EXPECT_EQ(r[0].raw, 1234);
  EXPECT_DOUBLE_EQ(r[0].celsius, 123.4);
  EXPECT_EQ(r[0].state(), std::to_string(123.4));
  EXPECT_DOUBLE_EQ(r[0].variance_c2, 0.1 * 0.1 / 12.0);
  EXPECT_TRUE(r[3].broken);  // open: the line-broken value
  EXPECT_EQ(r[3].raw, kLineBrokenValue);
  EXPECT_TRUE(std::isnan(r[3].celsius));
  EXPECT_EQ(r[3].state(), "line broken");
  put("R4010", 0xFFFE);  // the installed bits (treg::kInstalled): channel 0 taken out
  const auto out = plc.locked([&](ScanEngine&, Memory& m) { return cell->readings(m); });
  EXPECT_TRUE(out[0].broken);
  EXPECT_EQ(out[0].state(), "not installed");
}

TEST_F(TemperatureCellTest, FastScanFahrenheitAndAveraging) {
  setup(R"(
modules:
  temperature:
    scan: fast
    unit: F
    averaging: 4
    modules:
      - type: 2TC
        sensor: J
        channels: [{name: oven, plant: oven}, {name: room, temperature: 21.3}]
  plants:
    - {name: oven, ambient: 20, initial: 20, gain: 200, time_constant: 10, dead_time: 0, heater: Y0}
)",
        "ORG M1925\nOUT Y0\nEND\n");
  // Fast: 2TC updates every 1 s, 1 degree resolution; 21.3 degC = 70.34 degF -> 70 -> 700.
  scans(2000);
  EXPECT_EQ(sget("R1"), 700);
  // The oven heats towards 220 degC; the 4-sample moving average lags the plant.
  scans(100000);
  const double plant = cell->plant("oven")->temperature_c();
  EXPECT_NEAR(plant, 220, 0.1);
  const int16_t r0 = int16_t(get("R0"));
  EXPECT_EQ(r0 % 10, 0);  // whole degrees
  EXPECT_NEAR(r0 / 10.0, 220 * 9.0 / 5 + 32, 1.0);
}

TEST_F(TemperatureCellTest, NtcAndJisRtdModules) {
  setup(R"(
modules:
  temperature:
    averaging: 16
    readings: D100
    working: D200
    modules:
      - type: 6NTC
        r25: 10000
        beta: 3950
        channels: [{name: a, temperature: 37.3}, {name: hot, temperature: 180}]
  plants: []
)");
  scans(2100);  // 6NTC normal: 2 s for 6 channels
  EXPECT_EQ(sget("D100"), 373);
  EXPECT_EQ(sget("D101"), 1500);          // beyond plc_cell's -40..150 degC NTC range: saturated
  EXPECT_EQ(get("D201") & 0x3u, 0x2u);    // ... and abnormal
  EXPECT_EQ(get("D204") >> 8, 0x20u);     // NTC sensor code
}

TEST(TemperatureConfig, SteinhartHartAndJisOptions) {
  const TemperatureConfig c = parse_temperature_config(YAML::Load(R"(
modules:
  temperature:
    modules:
      - {type: 6NTC, steinhart_hart: [1.009249522e-3, 2.378405444e-4, 2.019202697e-7],
         channels: [{temperature: 25}]}
      - {type: 16RTD, sensor: PT1000, alpha: JIS, channels: [{temperature: 25}]}
)")["modules"], "c.yaml");
  ASSERT_EQ(c.modules.size(), 2u);
  EXPECT_TRUE(c.modules[0].use_sh);
  EXPECT_EQ(c.modules[1].sensor, SensorKind::Pt1000);
  EXPECT_EQ(c.modules[1].sensor_code(), 0x13);
  Memory mem;
  TemperatureCell cell(c, mem);
  cell.before_inputs(0);  // t = 0: the first channel of each module is converted
  // 25 degC through the Steinhart-Hart curve and the JIS Pt1000 curve comes back as 25.0.
  EXPECT_NEAR(cell.channels()[0].value_c, 25.0, 1e-6);
  EXPECT_NEAR(cell.channels()[6].value_c, 25.0, 1e-6);
}

TEST_F(TemperatureCellTest, ConfigErrorsNameTheKey) {
  const auto bad = config_error;
  EXPECT_NE(bad("modules: {temperature: {modules: [{type: 7TC}]}}").find("unknown module"), std::string::npos);
  EXPECT_NE(bad("modules: {temperature: {averaging: 3, modules: [{type: 2TC}]}}").find("averaging"), std::string::npos);
  EXPECT_NE(bad("modules: {temperature: {modules: [{type: 6RTD, sensor: K}]}}").find("PT100"), std::string::npos);
  EXPECT_NE(bad("modules: {temperature: {modules: [{type: 16TC}, {type: 16TC}, {type: 2TC}]}}").find("32"),
            std::string::npos);
  EXPECT_NE(bad("modules: {temperature: {modules: [{type: 2TC, channels: [{plant: x}]}]}}").find("unknown plant"),
            std::string::npos);
  EXPECT_NE(bad("modules: {temperature: {scann: fast}}").find("unknown key"), std::string::npos);
}

// modules: is read by the cell's one YAML reader (config/yaml_reader.h): each error names
// file:line:column and the key, and a channel's name, which becomes the topic
// ~temperature/<name>, is letters, digits and _ (docs/analog-and-temperature.md).
TEST(TemperatureConfig, ErrorsNameFileLineAndKey) {
  const std::string tc6 = "modules:\n  temperature:\n    modules:\n      - type: 6TC\n        channels:\n";
  EXPECT_EQ(config_error(tc6 + "          - {name: zone-1, temperature: 100}\n"),
            "c.yaml:6:20: error: key 'modules.temperature.modules[0].channels[0].name': a temperature channel name "
            "is letters, digits and _ (it becomes a ROS topic name)");
  EXPECT_EQ(config_error(tc6 + "          - {name: zone1, open: maybe}\n"),
            "c.yaml:6:33: error: key 'modules.temperature.modules[0].channels[0].open': expected 0/1 or true/false");
  EXPECT_EQ(config_error("modules:\n  plants:\n    - {name: oven, gain: -1}\n"),
            "c.yaml:3:26: error: key 'modules.plants[0].gain': value -1 out of range [0, 3000]");
  EXPECT_EQ(config_error("modules:\n  temperature:\n    loops:\n      - {name: oven, sv: M100}\n"),
            "c.yaml:4:26: error: key 'modules.temperature.loops[0].sv': expected an R or D register");
  EXPECT_EQ(config_error("modules:\n  analog:\n    board: {type: B4AD, inputs: [{nam: a}]}\n"),
            "c.yaml:3:35: error: key 'modules.analog.board.inputs[0].nam': unknown key (expected one of: conditioning, "
            "current, name, offset, plant, plant_range, value)");
}

TEST(TemperatureConfig, AGoodModulesSectionReadsAsBefore) {
  const TemperatureConfig c = parse_temperature_config(YAML::Load(R"(
modules:
  temperature:
    unit: F
    readings: D10
    loops:
      - {name: oven, sv: R100, kc: D120}
    modules:
      - type: 6TC
        sensor: J
        channels: [{name: zone_1, plant: oven}, {name: Spare2, open: true}, {temperature: 40}]
  plants:
    - {name: oven, ambient: 20, gain: 300, time_constant: 600, heater: Y30}
  analog:
    board: {type: B4AD, inputs: [{name: level, current: true}]}
)")["modules"], "c.yaml");
  EXPECT_TRUE(c.fahrenheit);
  EXPECT_EQ(c.readings, parse_address("D10"));
  ASSERT_EQ(c.loops.size(), 1u);
  EXPECT_EQ(c.loops[0].sv, parse_address("R100"));
  EXPECT_TRUE(c.loops[0].has_kc);
  EXPECT_FALSE(c.loops[0].has_ki);
  ASSERT_EQ(c.modules.size(), 1u);
  EXPECT_EQ(c.modules[0].tc, TcType::J);
  ASSERT_EQ(c.modules[0].channels.size(), 3u);
  EXPECT_EQ(c.modules[0].channels[0].name, "zone_1");
  EXPECT_EQ(c.modules[0].channels[0].plant, "oven");
  EXPECT_EQ(c.modules[0].channels[1].name, "Spare2");
  EXPECT_TRUE(c.modules[0].channels[1].open);
  EXPECT_EQ(c.modules[0].channels[2].fixed_c, 40);
  ASSERT_EQ(c.plants.size(), 1u);
  EXPECT_EQ(c.plants[0].params.ambient_c, 20);
  EXPECT_EQ(c.plants[0].params.gain_c, 300);
  EXPECT_TRUE(c.plants[0].has_heater);
  EXPECT_EQ(c.plants[0].heater, parse_address("Y30"));
  ASSERT_EQ(c.analog.board.inputs.size(), 1u);
  EXPECT_EQ(c.analog.board.inputs[0].name, "level");
  EXPECT_TRUE(c.analog.board.inputs[0].current);
}

TEST(ThermalPlant, FirstOrderPlusDeadTime) {
  ThermalPlantParams p;
  p.ambient_c = 25, p.initial_c = 25, p.gain_c = 100, p.tau_s = 100, p.dead_time_s = 10;
  ThermalPlant plant(p);
  for (int i = 0; i < 9990; ++i) plant.step(1000, 1.0);  // 9.99 s: the power has not arrived
  EXPECT_NEAR(plant.temperature_c(), 25, 1e-9);
  for (int i = 0; i < 100010; ++i) plant.step(1000, 1.0);  // to t = 110 s: one tau after the delay
  EXPECT_NEAR(plant.temperature_c(), 25 + 100 * (1 - std::exp(-1.0)), 0.05);
  for (int i = 0; i < 2000; ++i) plant.step(1000000, 0.0);  // long off: back to ambient
  EXPECT_NEAR(plant.temperature_c(), 25, 1e-6);
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
