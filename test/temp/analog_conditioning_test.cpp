// The TRi FMD1616's ADC/DAC conditioning on the simulated analog channels: moving
// average (TRi manual 5.2.6, 5.5.5), gain (1 + x/10000) (5.5.1, 5.5.3) and zero offset
// (5.5.2, 5.5.4), with the manual's worked examples.
#include <gtest/gtest.h>

#include <algorithm>

#include "config_error.h"

#include "plc_cell/core/error.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/temp/analog_conditioning.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace temp {
namespace {

// The TRi's 12-bit ADC/DAC: counts 0..4095.
int32_t tri(int64_t sum, int samples, int gain, int offset) { return condition_code(sum, samples, gain, offset, 0, 4095); }

TEST(AnalogConditioning, TheManualsWorkedExamples) {
  // 5.5.1 example 2: ADC ch 8 reads 3230 for 4.000 V (3277); x = +146: 3230 x 1.0146 = 3277.
  EXPECT_EQ(tri(3230, 1, 146, 0), 3277);
  // 5.5.1 example 1: ADC ch 1 reads 2060 for 2.500 V (2048); x = -58: 2060 x 0.9942 = 2048.
  EXPECT_EQ(tri(2060, 1, -58, 0), 2048);
  // 5.5.3: SETDAC 1,2048 gave 2.480 V; x = 81 sends 2048 x 1.0081 = 2064.6 -> 2065, and a DAC
  // 0.992 low then puts out 2065 / 4096 x 5 V x 0.992 = 2.500 V (to a count).
  const int32_t up = tri(2048, 1, 81, 0);
  EXPECT_EQ(up, 2065);
  EXPECT_NEAR(up / 4096.0 * 5.0 * 0.992, 2.500, 5.0 / 4096);
  // 5.5.3 example 2: 2.515 V; x = -60 sends 2048 x 0.9940 = 2035.7 -> 2036, i.e. 2.500 V.
  const int32_t down = tri(2048, 1, -60, 0);
  EXPECT_EQ(down, 2036);
  EXPECT_NEAR(down / 4096.0 * 5.0 * 1.006, 2.500, 5.0 / 4096);
  // 5.5.2 / 5.5.4: the zero offset is added to the value.
  EXPECT_EQ(tri(2048, 1, 0, 100), 2148);
  EXPECT_EQ(tri(2048, 1, 0, -100), 1948);
  EXPECT_EQ(tri(2048, 1, 0, 0), 2048);
}

TEST(AnalogConditioning, AverageThenGainThenOffsetRoundedOnceHalfAwayFromZero) {
  // Average of the raw samples, not rounded before the gain: {1000, 1001} x 1.5 = 1500.75
  // -> 1501 (rounding the mean first would give 1001 x 1.5 = 1501.5 -> 1502).
  EXPECT_EQ(tri(2001, 2, 5000, 0), 1501);
  // Offset after gain: 1000 x 1.1 + 50 = 1150 (offset before gain would give 1155).
  EXPECT_EQ(tri(1000, 1, 1000, 50), 1150);
  // Exact halves, both signs: away from zero.
  EXPECT_EQ(tri(3, 2, 0, 0), 2);                                   // 1.5
  EXPECT_EQ(tri(5, 2, 0, 0), 3);                                   // 2.5
  EXPECT_EQ(condition_code(5000, 1, 1, 0, -8192, 8191), 5001);     // 5000.5
  EXPECT_EQ(condition_code(-5000, 1, 1, 0, -8192, 8191), -5001);   // -5000.5
  EXPECT_EQ(condition_code(-3, 2, 0, 0, -8192, 8191), -2);         // -1.5
  EXPECT_EQ(condition_code(-5, 2, 0, 0, -8192, 8191), -3);         // -2.5
  // Just off a half: the exact fraction decides (1234 x 1.0001 = 1234.1234).
  EXPECT_EQ(tri(1234, 1, 1, 0), 1234);
  EXPECT_EQ(tri(4999, 1, -1, -100), 4095);  // 4998.5 - 100 = 4898.5 -> clamped
}

TEST(AnalogConditioning, ClampedToTheCodeRangeAtBothEnds) {
  EXPECT_EQ(tri(4095, 1, 146, 0), 4095);    // 4154.8
  EXPECT_EQ(tri(4000, 1, 0, 100), 4095);    // 4100
  EXPECT_EQ(tri(3995, 1, 0, 100), 4095);    // exactly the top
  EXPECT_EQ(tri(3994, 1, 0, 100), 4094);
  EXPECT_EQ(tri(0, 1, 0, -1), 0);           // -1
  EXPECT_EQ(tri(50, 1, 0, -100), 0);        // -50
  EXPECT_EQ(tri(100, 1, 0, -100), 0);
  EXPECT_EQ(tri(101, 1, 0, -100), 1);
  EXPECT_EQ(tri(0, 1, -9999, 0), 0);
  EXPECT_EQ(condition_code(-8192, 1, 0, -100, -8192, 8191), -8192);  // a bipolar code's ends
  EXPECT_EQ(condition_code(8191, 1, 0, 100, -8192, 8191), 8191);
  EXPECT_EQ(condition_code(-8100, 1, 200, 0, -8192, 8191), -8192);   // -8262
}

TEST(AnalogConditioning, TheFifoHoldsTheLastNSamples) {
  ConditioningDef d;
  d.enabled = true;
  d.average = 3;
  ConditionedChannel c(d);
  // Before the buffer is full the mean is over the samples taken so far.
  EXPECT_EQ(c.sample(300, 0, 4095), 300);
  EXPECT_EQ(c.sample(600, 0, 4095), 450);
  EXPECT_EQ(c.sample(900, 0, 4095), 600);
  EXPECT_EQ(c.sample(0, 0, 4095), 500);   // 300 dropped: (600 + 900 + 0) / 3
  EXPECT_EQ(c.sample(0, 0, 4095), 300);
  EXPECT_EQ(c.sample(0, 0, 4095), 0);
  d.average = 1;  // 1: the latest sample
  ConditionedChannel one(d);
  EXPECT_EQ(one.sample(7, 0, 4095), 7);
  EXPECT_EQ(one.sample(4000, 0, 4095), 4000);
  d.average = 9;
  ConditionedChannel nine(d);
  for (int k = 1; k <= 9; ++k) EXPECT_EQ(nine.sample(900, 0, 4095), 900 * k / k);
  for (int k = 1; k <= 9; ++k) EXPECT_EQ(nine.sample(0, 0, 4095), condition_code(900 * (9 - k), 9, 0, 0, 0, 4095)) << k;
}

// A cell with the analog modules of yaml; inputs driven by name, IR and outputs read.
class CondCell {
 public:
  explicit CondCell(const std::string& yaml, const std::string& program = "ORG M1925\nEND\n") {
    plc.locked([&](ScanEngine& e, Memory& m) {
      cell = make_temperature_cell(YAML::Load(yaml), "c.yaml", m);
      e.add_hook(cell.get());
      return 0;
    });
    plc.load_program_text(program, "c.il");
    EXPECT_TRUE(plc.set_mode(RunMode::Run));
  }
  ~CondCell() {
    plc.locked([&](ScanEngine& e, Memory&) {
      e.remove_hook(cell.get());
      return 0;
    });
  }
  int32_t reg(const std::string& a) { return int16_t(plc.read(parse_address(a), 1).at(0)); }
  void put(const std::string& a, uint32_t v) { plc.write(parse_address(a), {v}); }
  void drive(const std::string& name, double v) {
    std::string why;
    Quantity q;
    q.value = v;
    q.unit = Unit::Volt;
    ASSERT_TRUE(cell->drive_analog_input(name, q, &why)) << why;
  }
  const std::vector<AnalogModules::Output>& outputs() { return cell->analog()->outputs(); }
  void scan() { plc.scan(t), t += 10000; }
  Plc plc;
  std::unique_ptr<TemperatureCell> cell;
  uint64_t t = 0;
};

// Volts giving exactly `steps` of the board's 12 bits on 0-10 V.
double board_volts(int steps) { return steps / 4095.0 * 10.0; }

TEST(AnalogConditioningCell, BoardInputsAreTheTrisTwelveBits) {
  CondCell c(R"(
modules:
  analog:
    board:
      type: B4AD
      inputs:
        - {name: ch8, conditioning: {gain: 146}}
        - {name: ch1, conditioning: {gain: -58}}
        - {name: plain}
        - {name: zero, conditioning: {offset: 100}}
)");
  c.drive("ch8", board_volts(3230));
  c.drive("ch1", board_volts(2060));
  c.drive("plain", board_volts(3230));
  c.scan();
  EXPECT_EQ(c.reg("D4072"), 4 * 3277);  // the manual's 3230 -> 3277, in the board's x 4 codes
  EXPECT_EQ(c.reg("D4073"), 4 * 2048);  // 2060 -> 2048
  EXPECT_EQ(c.reg("D4074"), 4 * 3230);  // not configured: unchanged
  EXPECT_EQ(c.reg("D4075"), 4 * 100);   // 0 V + 100 counts
}

TEST(AnalogConditioningCell, ModuleInputsWorkInFourteenBitCounts) {
  // 3230 / 2060 in the 12-bit format are 12920 / 8240 in 14 bits; the gain applies there
  // and the 12-bit format (D4042 = 5612H) shows the manual's results.
  CondCell c(R"(
modules:
  analog:
    modules:
      - type: 6AD
        code: unipolar
        signal: unipolar
        inputs:
          - {name: ch8, conditioning: {gain: 146}}
          - {name: ch1, conditioning: {gain: -58}}
          - {name: plain}
          - {name: lo, conditioning: {offset: 100}}
          - {name: hi, conditioning: {offset: -100}}
)");
  c.put("D4042", 0x5612);
  auto volts = [](int code14) { return code14 / 16383.0 * 10.0; };
  c.drive("ch8", volts(12920));
  c.drive("ch1", volts(8240));
  c.drive("plain", volts(12920));
  c.drive("hi", 10.0);
  c.scan();
  EXPECT_EQ(c.reg("R3840"), 3277);  // 12920 x 1.0146 = 13108.6 -> 13109, / 4
  EXPECT_EQ(c.reg("R3841"), 2048);  // 8240 x 0.9942 = 8192.2 -> 8192, / 4
  EXPECT_EQ(c.reg("R3842"), 3230);
  EXPECT_EQ(c.reg("R3843"), 25);    // 0 V + 100 fourteen-bit counts = 25 twelve-bit counts
  EXPECT_EQ(c.reg("R3844"), 4070);  // 16383 - 100 = 16283, / 4
  c.put("D4042", 0);
  c.put("D4006", 0x001F);  // valid 14 bits ...
  c.put("D4010", 0x0101);  // ... without the module's own averaging
  c.put("D4011", 0x0101);
  c.put("D4012", 0x0101);
  c.scan();
  EXPECT_EQ(c.reg("R3840"), 13109);
  EXPECT_EQ(c.reg("R3841"), 8192);
  EXPECT_EQ(c.reg("R3842"), 12920);
  EXPECT_EQ(c.reg("R3843"), 100);
  EXPECT_EQ(c.reg("R3844"), 16283);
}

TEST(AnalogConditioningCell, BipolarCodesClampAtBothEnds) {
  CondCell c(R"(
modules:
  analog:
    modules:
      - type: 6AD
        inputs:
          - {name: top, value: 10, conditioning: {offset: 100}}
          - {name: bottom, value: -10, conditioning: {offset: -100}}
          - {name: below, value: -10, conditioning: {offset: 100}}
          - {name: mid, value: 0, conditioning: {gain: 9999, offset: -7}}
)");
  c.put("D4006", 0x000F);
  c.put("D4010", 0x0101);
  c.put("D4011", 0x0101);
  c.scan();
  EXPECT_EQ(c.reg("R3840"), 8191);
  EXPECT_EQ(c.reg("R3841"), -8192);
  EXPECT_EQ(c.reg("R3842"), -8092);
  EXPECT_EQ(c.reg("R3843"), -7);  // the gain scales about code 0, the offset adds
}

TEST(AnalogConditioningCell, AStepReachesTheInputOverNScans) {
  // N = 4, one sample per scan: the step 0 -> 16383 shows as exact quarters.
  CondCell c(R"(
modules:
  analog:
    modules:
      - type: 6AD
        code: unipolar
        signal: unipolar
        inputs:
          - {name: avg4, conditioning: {average: 4}}
          - {name: avg9, conditioning: {average: 9}}
          - {name: plain}
)");
  c.put("D4006", 0x0007);  // valid 14 bits, module averaging 1
  c.put("D4010", 0x0101);
  c.put("D4011", 0x0001);
  for (int k = 0; k < 10; ++k) c.scan();
  EXPECT_EQ(c.reg("R3840"), 0);
  for (const char* n : {"avg4", "avg9", "plain"}) c.drive(n, 10.0);
  const int32_t four[] = {4096, 8192, 12287, 16383, 16383};  // 16383 x k/4, half away from zero
  for (int k = 0; k < 5; ++k) {
    c.scan();
    EXPECT_EQ(c.reg("R3840"), four[k]) << k;
    EXPECT_EQ(c.reg("R3841"), condition_code(16383LL * std::min(k + 1, 9), 9, 0, 0, 0, 16383)) << k;
    EXPECT_EQ(c.reg("R3842"), 16383) << k;  // not configured: the step at once
  }
  for (int k = 5; k < 9; ++k) c.scan();
  EXPECT_EQ(c.reg("R3841"), 16383);  // the 9th sample of 10 V
  // And back: the first scans before a full buffer average what they have.
  CondCell fresh(R"(
modules:
  analog:
    modules:
      - {type: 6AD, code: unipolar, signal: unipolar, inputs: [{name: a, value: 5, conditioning: {average: 4}}]}
)");
  fresh.put("D4006", 1);
  fresh.put("D4010", 1);
  fresh.scan();
  EXPECT_EQ(fresh.reg("R3840"), 8192);  // one sample of 5 V, not 8192 / 4
  fresh.drive("a", 0);
  fresh.scan();
  EXPECT_EQ(fresh.reg("R3840"), 4096);  // (8192 + 0) / 2
}

TEST(AnalogConditioningCell, TheModulesOwnAverageComesFirst) {
  // D4010 = 2 averages the module's samples; the conditioning's FIFO then takes what the
  // module delivers each scan (8192 on the step: (0 + 16383) / 2 rounded up).
  CondCell c(R"(
modules:
  analog:
    modules:
      - {type: 6AD, code: unipolar, signal: unipolar, inputs: [{name: a, conditioning: {average: 2, offset: 1}}]}
)");
  c.put("D4006", 1);
  c.put("D4010", 2);
  c.scan();
  c.scan();
  EXPECT_EQ(c.reg("R3840"), 1);
  c.drive("a", 10.0);
  c.scan();
  EXPECT_EQ(c.reg("R3840"), 4097);   // (0 + 8192) / 2 + 1
  c.scan();
  EXPECT_EQ(c.reg("R3840"), 12289);  // (8192 + 16383) / 2 + 1 = 12288.5, rounded once
  c.scan();
  EXPECT_EQ(c.reg("R3840"), 16383);  // 16384 clamped
}

TEST(AnalogConditioningCell, NotConfiguredOrEmptyChangesNothing) {
  // The same channels without the key, with `conditioning: {}` (N = 1, x = 0, offset 0):
  // identical registers and outputs scan by scan, whatever the inputs do.
  auto yaml = [](const std::string& cond) {
    return "modules:\n  analog:\n    modules:\n      - type: 4A2D\n        inputs: [{name: a" + cond +
           "}, {name: b, current: true" + cond + "}]\n        outputs: [{name: o" + cond + "}, {name: p" + cond +
           "}]\n    board:\n      type: B2A1D\n      inputs: [{name: c" + cond + "}]\n      outputs: [{name: q" +
           cond + "}]\n";
  };
  const char* program = "ORG M1925\nMOV S=R3840 D=R3904\nMOV S=R3841 D=R3905\nMOV S=D4072 D=D4076\nEND\n";
  CondCell plain(yaml(""), program), empty(yaml(", conditioning: {}"), program);
  const double volts[] = {0, 3.3, -7.25, 10, 12, 4.999, -10};
  for (double v : volts) {
    for (CondCell* c : {&plain, &empty}) {
      c->drive("a", v);
      c->drive("c", v);
      std::string why;
      Quantity ma;
      ma.value = v * 2;
      ma.unit = Unit::Milliamp;
      ASSERT_TRUE(c->cell->drive_analog_input("b", ma, &why)) << why;
      c->scan();
    }
    for (const char* r : {"R3840", "R3841", "D4072"}) EXPECT_EQ(plain.reg(r), empty.reg(r)) << r << " at " << v;
    ASSERT_EQ(plain.outputs().size(), empty.outputs().size());
    for (size_t i = 0; i < plain.outputs().size(); ++i)
      EXPECT_EQ(plain.outputs()[i].signal, empty.outputs()[i].signal) << i << " at " << v;
  }
  EXPECT_EQ(plain.reg("R3840"), -8192);  // the last input really was -10 V
}

TEST(AnalogConditioningCell, OutputsSendTheConditionedCode) {
  CondCell c(R"(
modules:
  analog:
    board:
      type: B2DA
      outputs:
        - {name: dac1, conditioning: {gain: 81}}
        - {name: dac2, conditioning: {gain: -60}}
    modules:
      - type: 4DA
        code: unipolar
        signal: unipolar
        outputs:
          - {name: gain, conditioning: {gain: 81}}
          - {name: top, conditioning: {offset: 100}}
          - {name: bottom, conditioning: {offset: -100}}
          - {name: over, conditioning: {offset: -100}}
      - type: 2DA
        outputs:
          - {name: zero, conditioning: {offset: 100}}
          - {name: plain}
)", "ORG M1925\nMOV S=8192 D=D4076\nMOV S=8192 D=D4077\nMOV S=8192 D=R3904\nMOV S=16383 D=R3905\n"
    "MOV S=50 D=R3906\nMOV S=20000 D=R3907\nMOV S=0 D=R3908\nMOV S=0 D=R3909\nEND\n");
  c.scan();
  const auto& o = c.outputs();
  ASSERT_EQ(o.size(), 8u);
  auto u10 = [](int32_t code) { return ao_signal(AnalogRange{false, true, false}, code, false); };
  auto b10 = [](int32_t code) { return ao_signal(AnalogRange{true, true, false}, code, true); };
  // The order: the 4DA, the 2DA, then the board.
  EXPECT_DOUBLE_EQ(o[0].signal, u10(8258));    // 8192 x 1.0081 = 8258.4
  EXPECT_DOUBLE_EQ(o[1].signal, 10.0);         // 16483 clamped to 16383
  EXPECT_DOUBLE_EQ(o[2].signal, 0.0);          // -50 clamped to 0
  EXPECT_DOUBLE_EQ(o[3].signal, u10(16283));   // 20000 taken as 16383 first, then - 100
  EXPECT_DOUBLE_EQ(o[4].signal, b10(100));     // bipolar: 0 V + 100 counts
  EXPECT_DOUBLE_EQ(o[5].signal, b10(0));       // not configured
  // The board's 12 bits: 2048 steps x 1.0081 = 2064.6 -> 2065; x 0.9940 = 2035.7 -> 2036.
  EXPECT_DOUBLE_EQ(o[6].signal, 2065 / 4095.0 * 10);
  EXPECT_DOUBLE_EQ(o[7].signal, 2036 / 4095.0 * 10);
  // A DAC 0.8 % low, as in the manual's 2.480 V example, then puts out the set value to a step.
  EXPECT_NEAR(o[6].signal * 0.992, 2048 / 4095.0 * 10, 10 / 4095.0);
  EXPECT_NEAR(o[7].signal * 1.006, 2048 / 4095.0 * 10, 10 / 4095.0);
  // Watchdog: not serviced for 0.5 s, an output is 0 V whatever its offset.
  c.plc.set_mode(RunMode::Stop);
  for (int k = 0; k < 50; ++k) c.scan();
  EXPECT_TRUE(o[4].watchdog);
  EXPECT_EQ(o[4].signal, 0.0);
}

TEST(AnalogConditioningConfig, ErrorsSayWhereAndWhy) {
  auto in = [](const std::string& cond) {
    return "modules:\n  analog:\n    modules:\n      - type: 4A2D\n        inputs:\n          - {name: a, "
           "conditioning: " + cond + "}\n";
  };
  auto out = [](const std::string& cond) {
    return "modules:\n  analog:\n    modules:\n      - type: 4A2D\n        outputs:\n          - {name: a, "
           "conditioning: " + cond + "}\n";
  };
  const std::string k = "key 'modules.analog.modules[0].inputs[0].conditioning";
  EXPECT_EQ(config_error(in("{average: 0}")),
            "c.yaml:6:47: error: " + k + ".average': moving average samples: 0 out of range 1..9");
  EXPECT_EQ(config_error(in("{average: 10}")),
            "c.yaml:6:47: error: " + k + ".average': moving average samples: 10 out of range 1..9");
  EXPECT_EQ(config_error(in("{average: 2.5}")),
            "c.yaml:6:47: error: " + k + ".average': moving average samples: a whole number 1..9, got 2.5");
  EXPECT_EQ(config_error(in("{offset: 101}")),
            "c.yaml:6:46: error: " + k + ".offset': zero offset in counts: 101 out of range -100..100");
  EXPECT_EQ(config_error(in("{offset: -101}")),
            "c.yaml:6:46: error: " + k + ".offset': zero offset in counts: -101 out of range -100..100");
  EXPECT_EQ(config_error(in("{gain: 1.0146}")),
            "c.yaml:6:44: error: " + k + ".gain': gain x of (1 + x/10000): a whole number -9999..9999, got 1.0146");
  EXPECT_EQ(config_error(in("{gain: 10000}")),
            "c.yaml:6:44: error: " + k + ".gain': gain x of (1 + x/10000): 10000 out of range -9999..9999");
  EXPECT_EQ(config_error(in("{gain: -10000}")),
            "c.yaml:6:44: error: " + k + ".gain': gain x of (1 + x/10000): -10000 out of range -9999..9999");
  EXPECT_EQ(config_error(in("{gain: big}")),
            "c.yaml:6:44: error: " + k + ".gain': gain x of (1 + x/10000): a whole number -9999..9999, got big");
  EXPECT_EQ(config_error(in("{gian: 5}")),
            "c.yaml:6:38: error: " + k + ".gian': unknown key (expected one of: average, gain, offset)");
  EXPECT_EQ(config_error(in("5")), "c.yaml:6:37: error: " + k + "': expected a mapping {average, gain, offset}");
  const std::string ko = "key 'modules.analog.modules[0].outputs[0].conditioning";
  EXPECT_EQ(config_error(out("{average: 4, gain: 81}")),
            "c.yaml:6:47: error: " + ko + ".average': an output has no moving average (the TRi averages ADC readings only)");
  EXPECT_EQ(config_error(out("{offset: 200}")),
            "c.yaml:6:46: error: " + ko + ".offset': zero offset in counts: 200 out of range -100..100");
  // A channel the module does not have.
  EXPECT_NE(config_error("modules:\n  analog:\n    modules:\n      - type: 6AD\n        outputs: [{conditioning: {gain: 1}}]\n")
                .find("c.yaml:5:18: error: key 'modules.analog.modules[0].outputs': a list of at most 0 outputs for a 6AD"),
            std::string::npos);
  EXPECT_NE(config_error("modules:\n  analog:\n    board:\n      type: B2DA\n      inputs: [{conditioning: {gain: 1}}]\n")
                .find("key 'modules.analog.board.inputs': a list of at most 0 inputs for a B2DA"),
            std::string::npos);
  EXPECT_NE(config_error("modules:\n  analog:\n    modules:\n      - type: 2A4TC\n        inputs: [{}, {}, {conditioning: {}}]\n")
                .find("a list of at most 2 inputs for a 2A4TC"),
            std::string::npos);
  // The extremes are accepted.
  EXPECT_EQ(config_error(in("{average: 1, gain: -9999, offset: -100}")), "no error");
  EXPECT_EQ(config_error(in("{average: 9, gain: 9999, offset: 100}")), "no error");
  EXPECT_EQ(config_error(out("{gain: 81, offset: -100}")), "no error");
}

TEST(AnalogConditioningConfig, ARejectedConfigChangesNothing) {
  CondCell c(R"(
modules:
  analog:
    board: {type: B4AD, inputs: [{name: a, conditioning: {offset: 100}}]}
)");
  c.scan();
  EXPECT_EQ(c.reg("D4072"), 400);
  bool threw = false;
  c.plc.locked([&](ScanEngine&, Memory& m) {
    try {
      make_temperature_cell(YAML::Load("modules:\n  analog:\n    board: {type: B4AD, inputs: [{name: a, conditioning: "
                                       "{offset: 1000}}]}\n"), "c.yaml", m);
    } catch (const SourceError&) {
      threw = true;
    }
    return 0;
  });
  EXPECT_TRUE(threw);
  c.scan();
  EXPECT_EQ(c.reg("D4072"), 400);  // the running cell keeps its conditioning
}
}  // namespace
}  // namespace temp
}  // namespace plc_cell
