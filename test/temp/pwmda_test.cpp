// FUN139 HSPWM and the PWMDA analog output (manual Appendix 2) in virtual time.
#include <gtest/gtest.h>

#include <optional>

#include "../core/plc_fixture.h"
#include "plc_cell/core/error.h"
#include "plc_cell/temp/hspwm.h"
#include "plc_cell/temp/pwmda.h"
#include "plc_cell/temp/temp_functions.h"

namespace plc_cell {
namespace temp {
namespace {

TEST(Pwmda, TheManualsCurve) {
  // Uncalibrated: 879 -> 10 V, 1000 -> 11.41 V; trimmed (curve A): 1000 -> 10 V.
  EXPECT_NEAR(pwmda_voltage(0.879, false), 10.0, 0.05);  // 10.03 V: the curve's "879 -> 10 V"
  EXPECT_DOUBLE_EQ(pwmda_voltage(1.0, false), 11.41);
  EXPECT_DOUBLE_EQ(pwmda_voltage(0.0, false), 0.0);
  EXPECT_DOUBLE_EQ(pwmda_voltage(1.0, true), 10.0);
  EXPECT_DOUBLE_EQ(pwmda_voltage(0.5, true), 5.0);
  EXPECT_NEAR(hspwm_frequency_hz(1, 1), 9216.0, 0.5);  // "Pn = 1: 9.2 kHz"
}

FunctionTable table() {
  FunctionTable t = FunctionTable::with_core_functions();
  add_temperature_functions(t);  // as SoftCell::functions()
  return t;
}

class PwmdaTest : public PlcFixture {
 protected:
  PwmdaTest() : PlcFixture(table()) {}
  void setup(const std::string& yaml, const std::string& program) {
    plc.locked([&](ScanEngine& e, Memory&) {
      out = make_pwmda_outputs(YAML::Load(yaml), "c.yaml");
      e.add_hook(out.get());
      return 0;
    });
    load(program);
  }
  void TearDown() override {
    if (!out) return;
    plc.locked([&](ScanEngine& e, Memory&) {
      e.remove_hook(out.get());
      return 0;
    });
  }
  std::unique_ptr<PwmdaOutputs> out;
};

const char* kTwo = "modules:\n  pwmda:\n    - {name: speed, output: Y0}\n    - {name: valve, output: Y2, trim: hardware}\n";
const char* kProgram =
    "ORG M0\nFUN 139 Pw=0 Op=0 Rs=1 Pn=1 OR=R0 WR=R100\n"
    "ORG M1\nFUN 139 Pw=1 Op=1 Rs=1 Pn=1 OR=R1 WR=R102\nEND\n";

TEST_F(PwmdaTest, SettlesToTheManualsVoltagesWithin50ms) {
  setup(kTwo, kProgram);
  put("R0", 879);
  put("R1", 250);  // Op 1: 250 -> 75 % -> 7.5 V on the trimmed output
  put("M0", 1);
  put("M1", 1);
  scans(1);
  EXPECT_EQ(get("R100"), 879u);  // WR: the width being generated, the Pn
  EXPECT_EQ(get("R101"), 1u);
  scans(50);  // 50 ms: within the manual's conversion time
  EXPECT_NEAR(out->voltage(0), 10.0, 0.1);
  EXPECT_NEAR(out->voltage(1), 7.5, 0.1);
  scans(50);
  EXPECT_NEAR(out->voltage(0), 11.41 * 0.879, 1e-3);
  put("R0", 1000);
  scans(200, 500);  // a different scan period gives the same settled value
  EXPECT_NEAR(out->voltage(0), 11.41, 1e-3);
  put("M0", 0);  // EN off stops the pulse train: 0 V
  scans(100);
  EXPECT_NEAR(out->voltage(0), 0.0, 1e-3);
  EXPECT_EQ(get("R100"), 0u);
  const HsPwmChannel ch = plc.locked([](ScanEngine& e, Memory&) { return hspwm_channel(e, 1); });
  EXPECT_TRUE(ch.running);
  EXPECT_NEAR(ch.frequency_hz, 9216.0, 0.5);
}

// FUN139's generators belong to their PLC: a PLC made where a gone one stood (the same
// memory address, as a process that builds cell after cell gets) starts with none running.
TEST(HsPwm, ANewPlcStartsWithNoGeneratorRunning) {
  std::optional<Plc> plc;
  plc.emplace(table());
  const void* first_at = &*plc;
  plc->load_program_text("ORG M0\nFUN 139 Pw=2 Op=0 Rs=1 Pn=1 OR=R0 WR=R100\nEND\n", "p.il");
  ASSERT_TRUE(plc->set_mode(RunMode::Run));  // (RUN clears the non-retentive M and R)
  plc->write(Address{Area::R, Width::Word, 0}, {500});
  plc->write(Address{Area::M, Width::Bit, 0}, {1});
  plc->scan(1000);
  EXPECT_TRUE(plc->locked([](ScanEngine& e, Memory&) { return hspwm_channel(e, 2); }).running);
  plc.reset();
  plc.emplace(table());
  ASSERT_EQ(&*plc, first_at);
  const HsPwmChannel ch = plc->locked([](ScanEngine& e, Memory&) { return hspwm_channel(e, 2); });
  EXPECT_FALSE(ch.running);
  EXPECT_EQ(ch.frequency_hz, 0.0);
}

TEST_F(PwmdaTest, StopSwitchesTheOutputOff) {
  setup(kTwo, kProgram);
  put("R0", 500);
  put("M0", 1);
  scans(100);
  EXPECT_NEAR(out->voltage(0), 5.705, 1e-3);
  plc.set_mode(RunMode::Stop);
  scans(100);
  EXPECT_NEAR(out->voltage(0), 0.0, 1e-3);
}

TEST_F(PwmdaTest, ConfigAndOperandErrors) {
  EXPECT_THROW(parse_pwmda_config(YAML::Load("[{output: Y1}]"), "c.yaml"), SourceError);
  EXPECT_THROW(parse_pwmda_config(YAML::Load("[{output: Y0}, {output: Y0}]"), "c.yaml"), SourceError);
  EXPECT_THROW(parse_pwmda_config(YAML::Load("[{output: Y4, trim: soft}]"), "c.yaml"), SourceError);
  EXPECT_EQ(parse_pwmda_config(YAML::Load("[{output: Y6}]"), "c.yaml").at(0).pw, 3);
  EXPECT_THROW(plc.load_program_text("ORG M0\nFUN 139 Pw=4 Op=0 Rs=1 Pn=1 OR=R0 WR=R100\nEND\n", "t.il"), Error);
  EXPECT_THROW(plc.load_program_text("ORG M0\nFUN 139 Pw=0 Op=2 Rs=1 Pn=1 OR=R0 WR=R100\nEND\n", "t.il"), Error);
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
