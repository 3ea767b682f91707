// FUN33 LCNV and FUN32 ADCNV with the manual's 4-20 mA examples (A:6202, A:6375).
#include <gtest/gtest.h>

#include "../core/plc_fixture.h"
#include "plc_cell/core/error.h"
#include "plc_cell/temp/linear_conversion.h"
#include "plc_cell/temp/temp_functions.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace temp {
namespace {

const int kS[6] = {0, 3000, 6000, 9000, 12000, 16383};

TEST(LinearConvert, TheManualsExamples) {
  // Input: a 4-20 mA transmitter read on 0-20 mA, Ts = 3276, 16383, 0, 16383.
  const int in[6] = {-4094, -345, 3405, 7155, 10904, 16383};
  // Output: 4-20 mA on a 0-20 mA output, Ts = 0, 16383, 3276, 16383.
  const int out[6] = {3276, 5676, 8076, 10476, 12876, 16383};
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(linear_convert(kS[i], 3276, 16383, 0, 16383), in[i], 1) << kS[i];
    EXPECT_EQ(linear_convert(kS[i], 0, 16383, 3276, 16383), out[i]) << kS[i];
  }
  EXPECT_EQ(linear_convert(5, 7, 7, 100, 200), 100);          // Smin = Smax
  EXPECT_EQ(linear_convert(-2, 0, 1, 0, 30000), -32768);      // saturates to 16 bits
  EXPECT_EQ(linear_convert(50, 0, 100, 200, 100), 150);       // a falling line
}

FunctionTable table() {
  FunctionTable t = FunctionTable::with_core_functions();
  add_temperature_functions(t);  // as SoftCell::functions()
  return t;
}

class LcnvTest : public PlcFixture {
 protected:
  LcnvTest() : PlcFixture(table()) {}
};

TEST_F(LcnvTest, Fun33InputExampleAsTheManualWritesIt) {
  load("ORG M0\nFUN 33 S=R0 Ts=R1000 D=R50 N=6\nEND\n");
  const uint32_t ts[4] = {3276, 16383, 0, 16383};
  for (int k = 0; k < 4; ++k) put("R" + std::to_string(1000 + k), ts[k]);
  for (int i = 0; i < 6; ++i) put("R" + std::to_string(i), kS[i]);
  scans(1);
  EXPECT_EQ(sget("R50"), 0);  // M0 off: nothing
  put("M0", 1);
  scans(1);
  const int expect[6] = {-4094, -345, 3405, 7155, 10904, 16383};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(sget("R" + std::to_string(50 + i)), expect[i], 1) << i;
}

TEST_F(LcnvTest, Fun32IsTheManualsOffsetFormula) {
  load("ORG M1925\nFUN 32 Md=0 S=R0 D=R10 N=3\nFUN 32 Md=1 S=R20 D=R30 N=2\nEND\n");
  put("R0", 16383);   // 20 mA, unipolar code -> (16383 - 3276) x 20/16 = 16383.75 -> 16383
  put("R1", 3276);    // 4 mA -> 0
  put("R2", 1000);    // below 4 mA (a broken loop) -> 0
  put("R20", static_cast<uint16_t>(-4916));  // 4 mA in bipolar code: -4916 + 8192 - 3276 = 0
  put("R21", 0);      // 10 mA bipolar (8192 unipolar): (8192 - 3276) x 20/16 = 6145
  scans(1);
  EXPECT_EQ(sget("R10"), 16383);
  EXPECT_EQ(sget("R11"), 0);
  EXPECT_EQ(sget("R12"), 0);
  EXPECT_EQ(sget("R30"), 0);
  EXPECT_EQ(sget("R31"), 6145);
}

TEST_F(LcnvTest, OperandChecks) {
  EXPECT_THROW(plc.load_program_text("ORG M0\nFUN 32 Md=2 S=R0 D=R10 N=1\nEND\n", "t.il"), Error);
  EXPECT_THROW(plc.load_program_text("ORG M0\nFUN 33 S=R0 Ts=R10 D=R20 N=0\nEND\n", "t.il"), Error);
  // A count that runs off the register area stops at its end.
  load("ORG M1925\nFUN 33 S=R0 Ts=R10 D=D3998 N=R100\nEND\n");
  put("R100", 50);
  put("R11", 10), put("R13", 10), put("R0", 4), put("R1", 5), put("R2", 6);
  scans(1);
  EXPECT_EQ(get("D3998"), 4u);
  EXPECT_EQ(get("D3999"), 5u);
}

// The offset output end to end: FUN33 puts 0..16383 on 4-20 mA of a 2DA's 0-20 mA range.
TEST_F(LcnvTest, OffsetOutputThroughA2DA) {
  std::unique_ptr<TemperatureCell> cell;
  plc.locked([&](ScanEngine& e, Memory& m) {
    cell = make_temperature_cell(YAML::Load(R"(
modules:
  analog:
    modules:
      - {type: 2DA, code: unipolar, signal: unipolar, outputs: [{name: valve, current: true}]}
)"), "c.yaml", m);
    e.add_hook(cell.get());
    return 0;
  });
  load("ORG M1925\nFUN 33 S=R0 Ts=R1000 D=R3904 N=1\nEND\n");
  put("R1000", 0), put("R1001", 16383), put("R1002", 3276), put("R1003", 16383);
  const double ma[3] = {4.0, 12.0, 20.0};
  const int s[3] = {0, 8192, 16383};
  for (int k = 0; k < 3; ++k) {
    put("R0", s[k]);
    scans(1);
    EXPECT_NEAR(cell->analog()->outputs()[0].signal, ma[k], 20.0 / 16383) << s[k];
  }
  plc.locked([&](ScanEngine& e, Memory&) {
    e.remove_hook(cell.get());
    return 0;
  });
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
