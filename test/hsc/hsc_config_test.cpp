// The counters: section of the cell YAML, with the manual's FP-08 example.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "plc_cell/core/error.h"
#include "plc_cell/hsc/hsc_config.h"

namespace plc_cell {
namespace hsc {
namespace {

HscConfig parse(const std::string& text) { return parse_hsc_config(YAML::Load(text)["counters"], "cell.yaml"); }

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const SourceError& e) {
    return e.diagnostics().at(0).to_string();
  }
  return "";
}

// Manual §10.4.1, FP-08: HSC0 unused, HSC1 as HST1, HSC2 MD7 with MASK (inverted),
// HSC3 MD2 with R on X13, HSC6 MD0 U=X10 D=X2. X10 is HSC2's MASK too.
const char* kFp08 =
    "counters:\n"
    "  hsc1: {type: timer}\n"
    "  hsc2: {mode: MD7, mask: true, invert: [mask]}\n"
    "  hsc3: {mode: MD2, b: X13}\n"
    "  hsc6: {mode: MD0, a: X10, b: X2}\n";

TEST(HscConfig, Fp08ExampleReportsTheDoubleUseOfX10) {
  const std::string e = error_of(kFp08);
  EXPECT_NE(e.find("cell.yaml:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("counters.hsc6.a"), std::string::npos) << e;
  EXPECT_NE(e.find("X10 is already used as the MASK input of HSC2 (line 3)"), std::string::npos) << e;
}

TEST(HscConfig, Fp08ExampleWithTheConflictResolved) {
  const HscConfig c = parse(
      "counters:\n"
      "  hsc1: {type: timer}\n"
      "  hsc2: {mode: MD7, mask: true, invert: [mask]}\n"
      "  hsc3: {mode: MD2, b: X13}\n"
      "  hsc6: {mode: MD0, a: X11, b: X2, name: feeder}\n");
  EXPECT_FALSE(c.counters[0].used);
  EXPECT_TRUE(c.counters[1].used && c.counters[1].timer);
  EXPECT_EQ(c.counters[1].name, "hst1");
  const CounterDef& h2 = c.counters[2];
  EXPECT_EQ(h2.mode, Mode::ABx4);
  EXPECT_EQ(h2.pin_a, 8);
  EXPECT_EQ(h2.pin_b, 9);
  EXPECT_EQ(h2.pin_mask, 10);
  EXPECT_EQ(h2.pin_clear, kNoPin);
  EXPECT_TRUE(h2.inv_mask);
  EXPECT_FALSE(h2.inv_count);
  EXPECT_EQ(c.counters[3].mode, Mode::PR);
  EXPECT_EQ(c.counters[3].pin_a, 12);
  EXPECT_EQ(c.counters[3].pin_b, 13);
  EXPECT_EQ(c.counters[6].pin_a, 11);
  EXPECT_EQ(c.counters[6].pin_b, 2);
  EXPECT_EQ(c.counters[6].name, "feeder");
  EXPECT_FALSE(c.counters[4].used);
}

TEST(HscConfig, RejectsWhatTheManualForbids) {
  EXPECT_NE(error_of("counters:\n  hsc5: {mode: MD1, a: X3}\n").find("MD0, MD2 or MD4"), std::string::npos);
  EXPECT_NE(error_of("counters:\n  hsc5: {mode: MD4, a: X3, b: X4}\n").find("must be a pair"), std::string::npos);
  EXPECT_NE(error_of("counters:\n  hsc1: {mode: MD0, a: X2}\n").find("cannot take its U input on X2"),
            std::string::npos);
  EXPECT_NE(error_of("counters:\n  hsc4: {type: timer}\n").find("HSC0-HSC3"), std::string::npos);
  EXPECT_NE(error_of("counters:\n  hsc0: {mode: MD0}\n  interrupts: [X0+]\n").find("X0 is already used"),
            std::string::npos);
  EXPECT_NE(error_of("counters:\n  hsc0: {mode: MD9}\n").find("MD0 ... MD7"), std::string::npos);
  EXPECT_NE(error_of("counters:\n  hsc4: {mode: MD0, a: X16}\n").find("X0-X15"), std::string::npos);
}

TEST(HscConfig, InterruptsSourcesAndEdges) {
  const HscConfig c = parse(
      "counters:\n"
      "  interrupts: [X3+, X3-, X5-]\n"
      "  frequency_window: 50ms\n"
      "  sources:\n"
      "    - {name: belt, type: encoder, a: X0, hz: 1000, follow: Y0}\n"
      "    - {name: spindle, a: X4, rpm: 18000, per_rev: 8}\n"
      "  edges:\n"
      "    - {x: X3, steps: [[10ms, 1], [2ms, 0]]}\n");
  EXPECT_EQ(c.edge_interrupts, (std::vector<int>{6, 7, 11}));
  EXPECT_EQ(c.frequency_window_us, 50000u);
  ASSERT_EQ(c.sources.size(), 2u);
  EXPECT_EQ(c.sources[0].pin_b, 1);
  EXPECT_TRUE(c.sources[0].has_follow);
  EXPECT_DOUBLE_EQ(c.sources[1].hz, 2400.0);
  ASSERT_EQ(c.edges.size(), 2u);
  EXPECT_EQ(c.edges[0].t_ns, 2000000u);  // sorted by time
  EXPECT_FALSE(c.edges[0].level);
}

// A counter's and a pulse source's names become topics (~counters/<name>,
// ~sources/<name>/rate): letters, digits and _, checked where every topic name is.
TEST(HscConfig, NamesThatBecomeTopicsAreChecked) {
  EXPECT_EQ(error_of("counters:\n  hsc0: {mode: MD0, name: feed-1}\n"),
            "cell.yaml:2:27: error: key 'counters.hsc0.name': a counter name is letters, digits and _ "
            "(it becomes a ROS topic name)");
  EXPECT_EQ(error_of("counters:\n  sources:\n    - {name: 2disk, a: X0, hz: 10}\n"),
            "cell.yaml:3:14: error: key 'counters.sources.name': a pulse source name is letters, digits and _ "
            "(it becomes a ROS topic name)");
  const HscConfig c = parse("counters:\n  hsc0: {mode: MD0, name: Feed_1}\n  sources:\n    - {name: disk2, a: X4, hz: 10}\n");
  EXPECT_EQ(c.counters[0].name, "Feed_1");
  ASSERT_EQ(c.sources.size(), 1u);
  EXPECT_EQ(c.sources[0].name, "disk2");
}

TEST(HscConfig, CaptureAndFilters) {
  const HscConfig c = parse(
      "counters:\n  capture: [X3, x17]\n"
      "  filters: {X0-X3: 28kHz, x4-x7: 0.3ms, X12-X15: 1.8MHz, X16-X23: 2ms, X24-X35: 15ms}\n");
  EXPECT_TRUE(c.capture[3] && c.capture[17]);
  EXPECT_FALSE(c.capture[4]);
  for (int x = 0; x < 4; ++x) EXPECT_EQ(c.filter_ns[x], 17778u);  // 1/(2 x 28125 Hz), rounded
  EXPECT_EQ(c.filter_ns[7], 300000u);
  EXPECT_EQ(c.filter_ns[8], 0u);
  EXPECT_EQ(c.filter_ns[15], 278u);
  EXPECT_EQ(c.filter_ns[23], 2000000u);
  EXPECT_EQ(c.filter_ns[35], 15000000u);
}

TEST(HscConfig, CaptureAndFilterErrorsNameTheLine) {
  std::string e = error_of("counters:\n  capture: [X3, X36]\n");
  EXPECT_NE(e.find("cell.yaml:2:"), std::string::npos) << e;
  EXPECT_NE(e.find("'X36' is not an input X0-X35"), std::string::npos) << e;
  e = error_of("counters:\n  capture: [X3, X3]\n");
  EXPECT_NE(e.find("X3 is listed twice"), std::string::npos) << e;
  e = error_of("counters:\n  filters:\n    X16-X23: 28kHz\n");
  EXPECT_NE(e.find("cell.yaml:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("X16-X23 has a time-domain filter only"), std::string::npos) << e;
  e = error_of("counters:\n  filters: {X0-X3: 40kHz}\n");
  EXPECT_NE(e.find("14kHz, 28kHz, 56kHz, 112kHz, 225kHz, 450kHz, 900kHz, 1.8MHz"), std::string::npos) << e;
  e = error_of("counters:\n  filters: {X0-X3: 0.25ms}\n");
  EXPECT_NE(e.find("X0-X3 takes 1ms ... 15ms, 0.1ms ... 1.5ms"), std::string::npos) << e;
  e = error_of("counters:\n  filters: {X16-X23: 0.5ms}\n");
  EXPECT_NE(e.find("X16-X23 takes 1ms ... 15ms"), std::string::npos) << e;
  e = error_of("counters:\n  filters: {X0-X4: 2ms}\n");
  EXPECT_NE(e.find("'X0-X4' is not a filter group"), std::string::npos) << e;
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
