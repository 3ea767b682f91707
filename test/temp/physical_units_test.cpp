// Sensors driven in their own units, from the cell YAML to the register the program reads,
// through the plc_cell tool as a user runs it: thermocouple emf in mV (NIST ITS-90 tables),
// RTD and NTC resistance in ohm (IEC 60751), analog inputs in V and mA (the manual's codes).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "../core/run_tool.h"

namespace plc_cell {
namespace {

const std::string kDir = "/tmp/plc_cell_units_";

// Runs the cell `modules` text for 10 s of virtual time (every module has read every
// channel by then) and returns the watched registers as signed 16-bit values.
std::map<std::string, int> readings(const std::string& name, const std::string& modules, const std::string& watch) {
  std::ofstream(kDir + "p.il") << "ORG M0\nOUT M1\nEND\n";
  const std::string path = kDir + name + ".yaml";
  std::ofstream(path) << "cell: {program: plc_cell_units_p.il}\nmodules:\n" << modules;
  const auto r = testing::run_tool("sim --config " + path + " --duration 10s --watch " + watch);
  EXPECT_EQ(r.status, 0) << r.out;
  std::map<std::string, int> out;
  std::istringstream in(r.out);
  std::string line;
  while (std::getline(in, line)) {
    const auto eq = line.find(" = ");
    if (line[0] == '#' || eq == std::string::npos) continue;
    out[line.substr(0, eq)] = int(int16_t(uint16_t(std::stoul(line.substr(eq + 3)))));
  }
  return out;
}

std::string check_error(const std::string& name, const std::string& modules) {
  std::ofstream(kDir + "p.il") << "ORG M0\nOUT M1\nEND\n";
  const std::string path = kDir + name + ".yaml";
  std::ofstream(path) << "cell: {program: plc_cell_units_p.il}\nmodules:\n" << modules;
  const auto r = testing::run_tool("check --config " + path);
  EXPECT_EQ(r.status, 1) << r.out;
  const auto sim = testing::run_tool("sim --config " + path + " --duration 1s");
  EXPECT_EQ(sim.status, 1) << sim.out;
  EXPECT_EQ(r.out.rfind(sim.out, 0), 0u) << "check and sim disagree\n" << r.out << sim.out;
  return r.out;
}

}  // namespace

// NIST Monograph 175 table values (emf against a 0 degC reference, 1 uV): the reading is
// the table's temperature in 0.1 degC.
TEST(PhysicalUnits, ThermocoupleMillivoltsReadTheNistTemperature) {
  const auto r = readings("tc",
                          "  temperature:\n"
                          "    readings: R0\n"
                          "    modules:\n"
                          "      - type: 6TC\n"
                          "        sensor: K\n"
                          "        channels: [{value: 4.096 mV}, {value: -3.554 mV}, {value: 41.276 mV}]\n"
                          "      - type: 2TC\n"
                          "        sensor: J\n"
                          "        channels: [{value: 5.269 mV}, {value: -4.633 mV}]\n"
                          "      - type: 2TC\n"
                          "        sensor: T\n"
                          "        channels: [{value: 4.279 mV}, {value: '-3.379 mV'}]\n",
                          "R0,R1,R2,R6,R7,R8,R9");
  EXPECT_EQ(r.at("R0"), 1000);    // K 100 degC = 4.096 mV
  EXPECT_EQ(r.at("R1"), -1000);   // K -100 degC = -3.554 mV
  EXPECT_EQ(r.at("R2"), 10000);   // K 1000 degC = 41.276 mV
  EXPECT_EQ(r.at("R6"), 1000);    // J 100 degC = 5.269 mV
  EXPECT_EQ(r.at("R7"), -1000);   // J -100 degC = -4.633 mV
  EXPECT_EQ(r.at("R8"), 1000);    // T 100 degC = 4.279 mV
  EXPECT_EQ(r.at("R9"), -1000);   // T -100 degC = -3.379 mV
}

// The value is the hot junction's emf against 0 degC; the module's cold-junction
// compensation makes the reading independent of its terminal temperature.
TEST(PhysicalUnits, ThermocoupleReadingDoesNotDependOnTheColdJunction) {
  for (const char* cj : {"0", "25", "40", "-10"}) {
    const auto r = readings(std::string("cj") + cj,
                            std::string("  temperature:\n    modules:\n      - {type: 2TC, sensor: K, cold_junction: ") +
                                cj + ", channels: [{value: 4.096 mV}, {temperature: 100}]}\n",
                            "R0,R1");
    EXPECT_EQ(r.at("R0"), 1000) << "cold junction " << cj;
    EXPECT_EQ(r.at("R0"), r.at("R1")) << "cold junction " << cj;  // as 100 degC given in C
  }
}

// IEC 60751 (alpha 0.00385) table values; an NTC at its beta reference (R25 at 25 degC).
TEST(PhysicalUnits, ResistanceReadsTheIec60751Temperature) {
  const auto r = readings("rtd",
                          "  temperature:\n"
                          "    readings: R0\n"
                          "    modules:\n"
                          "      - type: 6RTD\n"
                          "        sensor: PT100\n"
                          "        channels: [{value: 138.5055 ohm}, {value: 60.2558 ohm}, {value: 100 ohm}, "
                          "{value: 390.4811 ohm}]\n"
                          "      - type: 6RTD\n"
                          "        sensor: PT1000\n"
                          "        channels: [{value: 1758.56 ohm}, {value: 1.38506 kohm}]\n"
                          "      - type: 6NTC\n"
                          "        r25: 10000\n"
                          "        beta: 3950\n"
                          "        channels: [{value: 10 kohm}, {value: 10000 ohm}]\n",
                          "R0,R1,R2,R3,R6,R7,R12,R13");
  EXPECT_EQ(r.at("R0"), 1000);   // Pt100 100 degC = 138.5055 ohm
  EXPECT_EQ(r.at("R1"), -1000);  // Pt100 -100 degC = 60.2558 ohm
  EXPECT_EQ(r.at("R2"), 0);      // R0
  EXPECT_EQ(r.at("R3"), 8500);   // Pt100 850 degC = 390.4811 ohm
  EXPECT_EQ(r.at("R6"), 2000);   // Pt1000 200 degC = 1758.56 ohm
  EXPECT_EQ(r.at("R7"), 1000);   // Pt1000 100 degC = 1385.055 ohm
  EXPECT_EQ(r.at("R12"), 250);   // NTC at its beta reference: R25 reads 25.0 degC
  EXPECT_EQ(r.at("R13"), 250);
}

// A signal beyond the module's range saturates at the range end and sets the abnormal
// bit (WR+1), like a temperature beyond it.
TEST(PhysicalUnits, BeyondTheModuleRangeSaturatesAndFlags) {
  const auto r = readings("sat",
                          "  temperature:\n"
                          "    readings: R0\n"
                          "    working: D0\n"
                          "    modules:\n"
                          "      - {type: 2TC, sensor: K, channels: [{value: -5.891 mV}, {value: 4.096 mV}]}\n",
                          "R0,R1,D1");
  EXPECT_EQ(r.at("R0"), -1900);  // K -270 degC = -5.891 mV, below the module's -190
  EXPECT_EQ(r.at("R1"), 1000);
  EXPECT_EQ(r.at("D1"), 1);      // channel 0 abnormal only
}

// 0-20 mA / 0-10 V (unipolar signal, span 10, unipolar code) in the default format
// (14-bit code, valid 12 bits: B1 = B0 = 0): code = x / span x 16383.
TEST(PhysicalUnits, AnalogInputsInVoltsAndMilliamps) {
  const auto r = readings("ai",
                          "  analog:\n"
                          "    modules:\n"
                          "      - type: 6AD\n"
                          "        code: unipolar\n"
                          "        signal: unipolar\n"
                          "        span: 10\n"
                          "        inputs: [{value: 4 mA}, {value: 12 mA}, {value: 20 mA}, {value: 0 V}, {value: 5 V},"
                          " {value: 10 V}]\n",
                          "R3840,R3841,R3842,R3843,R3844,R3845");
  EXPECT_EQ(r.at("R3840"), 3276);   // 4 mA: 16383 x 4/20 = 3276.6, the manual's 4-20 mA zero 3276
  EXPECT_EQ(r.at("R3841"), 9828);   // 12 mA: 9829.8 -> 9830, valid 12 bits
  EXPECT_EQ(r.at("R3842"), 16380);  // 20 mA: 16383, valid 12 bits
  EXPECT_EQ(r.at("R3843"), 0);
  EXPECT_EQ(r.at("R3844"), 8192);   // 5 V: mid-scale
  EXPECT_EQ(r.at("R3845"), 16380);  // 10 V
  // The B4AD board: 12 bits as 0..16380.
  const auto b = readings("board",
                          "  analog:\n    board:\n      type: B4AD\n"
                          "      inputs: [{value: 4 mA}, {value: 20 mA}, {value: 5 V}, {value: 10 V}]\n",
                          "D4072,D4073,D4074,D4075");
  EXPECT_EQ(b.at("D4072"), 3276);
  EXPECT_EQ(b.at("D4073"), 16380);
  EXPECT_EQ(b.at("D4074"), 8192);
  EXPECT_EQ(b.at("D4075"), 16380);
}

TEST(PhysicalUnits, BadUnitsAndRangesNameTheLine) {
  const std::string f = kDir;
  auto tc = [](const std::string& v) {
    return "  temperature:\n    modules:\n      - type: 2TC\n        sensor: K\n        channels:\n          - {value: " + v +
           "}\n";
  };
  EXPECT_NE(check_error("u1", tc("4.096 mv")).find(f + "u1.yaml:8:21: error: key 'modules.temperature.modules[0].channels[0].value': '4.096 mv': unknown unit 'mv'"),
            std::string::npos);
  EXPECT_NE(check_error("u2", tc("100 ohm")).find(f + "u2.yaml:8:21: error: key 'modules.temperature.modules[0].channels[0].value': a thermocouple's value is in mV"),
            std::string::npos);
  EXPECT_NE(check_error("u3", tc("60 mV")).find("u3.yaml:8:21: error: key 'modules.temperature.modules[0].channels[0].value': '60 mV' out of range -6.4577..54.8864 mV (type K, NIST ITS-90 -270..1372 C)"),
            std::string::npos);
  EXPECT_NE(check_error("u4", tc("4.096")).find("'4.096' has no unit"), std::string::npos);
  EXPECT_NE(check_error("u5", "  temperature:\n    modules: [{type: 6RTD, channels: [{value: 10 ohm}]}]\n")
                .find("u5.yaml:4:47: error: key 'modules.temperature.modules[0].channels[0].value': '10 ohm' out of range 18.5201..390.4811 ohm"),
            std::string::npos);
  EXPECT_NE(check_error("u6", "  temperature:\n    modules: [{type: 6NTC, channels: [{value: -5 ohm}]}]\n")
                .find("'-5 ohm' out of range: a resistance above 0 ohm"),
            std::string::npos);
  EXPECT_NE(check_error("u7", "  temperature:\n    modules: [{type: 6RTD, channels: [{value: 4 mV}]}]\n")
                .find("an RTD's value is in ohm"),
            std::string::npos);
  EXPECT_NE(check_error("u8", "  temperature:\n    modules: [{type: 6TC, channels: [{value: 4 mV, temperature: 3}]}]\n")
                .find("give one of plant, temperature, value"),
            std::string::npos);
  const std::string ai = "  analog:\n    modules:\n      - type: 6AD\n        inputs: [";
  EXPECT_NE(check_error("a1", ai + "{current: false, value: 12 mA}]\n")
                .find("a1.yaml:6:42: error: key 'modules.analog.modules[0].inputs[0].value': '12 mA' on a voltage (current: false) input"),
            std::string::npos);
  EXPECT_NE(check_error("a2", ai + "{value: 5 A}]\n").find("unknown unit 'A'"), std::string::npos);
  EXPECT_NE(check_error("a3", ai + "{value: 100 ohm}]\n").find("an analog input's value is in V or mA"), std::string::npos);
  EXPECT_NE(check_error("a4", ai + "{value: 45 V}]\n").find("'45 V' out of range -30..30 V"), std::string::npos);
  EXPECT_NE(check_error("f1", "  generation: FB\n  fb_temperature:\n    modules: [{type: 2AK4, outputs: Y16, channels: [{value: 4.096 mV}]}]\n")
                .find("the FB-series modules take a value in C only"),
            std::string::npos);
}

}  // namespace plc_cell
