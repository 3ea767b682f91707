// FUN141: register layout, defaults, the manual's error codes, unit conversion.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>

#include "plc_cell/motion/params.h"

namespace plc_cell {
namespace motion {
namespace {

TEST(Params, ManualExample3TableRoundTrips) {
  // Example 3 (R500-R523): R519 = A802H (limit X40 NC, DOG X2 NO), R520 = 0804H (CLR Y8, PG0 X4).
  uint16_t r[kParamWords] = {1, 2000, 2000, 0, 2, 0x04E0, 0x0007, 141, 0, 1000, 0, 5000, 0x0100,
                             0, 0, 0, 500, 0, 0, 0xA802, 0x0804, 100, 0, 10};
  const AxisParams p = AxisParams::from_registers(r);
  EXPECT_EQ(p.validate(), 0);
  EXPECT_EQ(p.p4_max, 460000);
  EXPECT_EQ(p.p9_rot, 0);
  EXPECT_EQ(p.p9_home, 1);
  EXPECT_EQ(p.dog_input(), 2);
  EXPECT_FALSE(p.dog_nc());
  EXPECT_EQ(p.limit_input(), 40);
  EXPECT_TRUE(p.limit_nc());
  EXPECT_EQ(p.pg0_input(), 4);
  EXPECT_FALSE(p.pg0_rear());
  EXPECT_EQ(p.clr_output(), 8);
  EXPECT_EQ(p.p16_zero, 100);
  EXPECT_EQ(p.p17_pg0, 10);
  uint16_t back[kParamWords];
  p.to_registers(back);
  for (int i = 0; i < kParamWords; ++i) EXPECT_EQ(back[i], r[i]) << "SR+" << i;
}

TEST(Params, DefaultsAreTheManuals) {
  const AxisParams p;
  EXPECT_EQ(p.validate(), 0);
  EXPECT_DOUBLE_EQ(p.acc_hz_per_s(), 92000.0);  // 460000 Hz in 5 s
  EXPECT_DOUBLE_EQ(p.dec_hz_per_s(), 92000.0);  // P12 = 0: P8
  EXPECT_EQ(p.dog_input(), -1);
  EXPECT_EQ(p.clr_output(), -1);
}

TEST(Params, EachOutOfRangeValueGivesTheManualsCode) {
  struct Case { void (*set)(AxisParams&); int code; };
  const Case cases[] = {
      {[](AxisParams& p) { p.p0_unit = 3; }, 1},
      {[](AxisParams& p) { p.p1_ppr = 0; }, 2},
      {[](AxisParams& p) { p.p2_per_rev = 0; }, 3},
      {[](AxisParams& p) { p.p2_per_rev = 1000000; }, 3},
      {[](AxisParams& p) { p.p3_res = 4; }, 4},
      {[](AxisParams& p) { p.p4_max = 921601; }, 5},
      {[](AxisParams& p) { p.p4_max = 0; }, 5},
      {[](AxisParams& p) { p.p5_start = -1; }, 6},
      {[](AxisParams& p) { p.p5_start = 921601; }, 6},
      {[](AxisParams& p) { p.p6_creep = 0; }, 7},
      {[](AxisParams& p) { p.p7_backlash = -1; }, 8},
      {[](AxisParams& p) { p.p8_acc_ms = 30001; }, 9},
      {[](AxisParams& p) { p.p9_home = 2; }, 10},
      {[](AxisParams& p) { p.p12_dec_ms = -5; }, 13},
      {[](AxisParams& p) { p.p13_interp_ms = 30001; }, 14},
      {[](AxisParams& p) { p.p14_ppr = 2000000; }, 15},
  };
  for (const auto& c : cases) {
    AxisParams p;
    c.set(p);
    EXPECT_EQ(p.validate(), c.code);
  }
  // Machine units: P4 = 153000 cm/min is in range but with A/B = 1 exceeds 921600 Hz.
  AxisParams m;
  m.p0_unit = 0;
  m.p1_ppr = 1000;
  m.p2_per_rev = 1000;
  m.p4_max = 5529;  // 5529 * 1000 / 6 = 921500 Hz
  m.p5_start = 10;
  EXPECT_EQ(m.validate(), 0);
  m.p4_max = 5530;  // 921667 Hz
  EXPECT_EQ(m.validate(), 5);
}

TEST(Params, UtToPulses) {
  AxisParams p;
  EXPECT_EQ(p.ut_to_pulses(12345), 12345);  // P0 = 1: Ut is one pulse
  p.p0_unit = 2;  // compound: stroke in mm
  p.p1_ppr = 2000;
  p.p2_per_rev = 5000;  // 5 mm per revolution
  p.p3_res = 2;         // Ut = 0.01 mm
  EXPECT_EQ(p.ut_to_pulses(500), 2000);   // 5.00 mm = one revolution
  EXPECT_EQ(p.ut_to_pulses(-250), -1000);
  EXPECT_EQ(p.pulses_to_ut(2000), 500);
  p.p3_res = 0;  // Ut = 1 mm
  EXPECT_EQ(p.ut_to_pulses(10), 4000);
  p.p14_ppr = 10000;  // P14 overrides P1
  EXPECT_EQ(p.ut_to_pulses(10), 20000);
  p.p0_unit = 0;  // machine: speed 60 cm/min = 10 mm/s = 2 rev/s = 20000 Hz
  EXPECT_DOUBLE_EQ(p.speed_hz(60), 20000.0);
}


// The message names the parameter, the value and the manual's range (section 11.6).
TEST(Params, ErrorNamesTheParameterTheValueAndTheRange) {
  struct Case {
    int n;
    int64_t v;
    bool machine;
    int code;
    const char* message;
  };
  const Case cases[] = {
      {0, 3, false, 1, "P0: 3 out of range 0..2"},
      {1, 0, false, 2, "P1: 0 out of range 1..65535"},
      {2, 1000000, false, 3, "P2: 1000000 out of range 1..999999"},
      {3, 7, false, 4, "P3: 7 out of range 0..3"},
      {4, 921601, false, 5, "P4: 921601 out of range 1..921600"},
      {4, 153001, true, 5, "P4: 153001 out of range 1..153000 (machine units, P0 = 0)"},
      {5, -1, false, 6, "P5: -1 out of range 0..921600"},
      {6, 15301, true, 7, "P6: 15301 out of range 1..15300 (machine units, P0 = 0)"},
      {7, 32768, false, 8, "P7: 32768 out of range 0..32767"},
      {8, 30001, false, 9, "P8: 30001 out of range 0..30000"},
      {12, -1, false, 13, "P12: -1 out of range 0..30000"},
      {13, 30001, false, 14, "P13: 30001 out of range 0..30000"},
      {14, 2000000, false, 15, "P14: 2000000 out of range 0..1999999"},
  };
  for (const Case& c : cases) {
    // Through FUN141's validation of a stored table...
    AxisParams p;
    if (c.machine) {
      p.p0_unit = 0;
      p.p4_max = 100;  // 100 cm/min with A = B = 2000: 16667 Hz, in range
      p.p5_start = 1;
      p.p6_creep = 1;
    }
    ASSERT_EQ(p.validate(), 0);
    p.set(c.n, c.v);
    ParamError e;
    EXPECT_EQ(p.validate(&e), c.code) << c.message;
    EXPECT_EQ(e.message, c.message);
    EXPECT_EQ(e.n, c.n);
    EXPECT_EQ(e.value, c.v);
    // ...and through the values as a service gives them.
    int64_t v[kParamCount];
    for (int k = 0; k < kParamCount; ++k) v[k] = p.get(k);
    v[c.n] = c.v;
    ParamError e2;
    EXPECT_FALSE(AxisParams::check_values(v, &e2)) << c.message;
    EXPECT_EQ(e2.message, c.message);
    EXPECT_EQ(e2.code, c.code);
  }
}

TEST(Params, P9BytesAreZeroOrOne) {
  AxisParams p;
  p.set(9, 0x0200);
  ParamError e;
  EXPECT_EQ(p.validate(&e), 10);
  EXPECT_EQ(e.message, "P9: 512 out of range: low byte (P9-0) 0..1, high byte (P9-1) 0..1 (0000H, 0001H, 0100H, 0101H)");
  for (int64_t ok : {0x000, 0x001, 0x100, 0x101}) {
    p.set(9, ok);
    EXPECT_EQ(p.validate(), 0) << ok;
  }
}

// Values the table's fields could not hold as given are refused before they are
// narrowed (a service argument); parameters without a manual code report code 0.
TEST(Params, ServiceValuesAreCheckedBeforeNarrowing) {
  const AxisParams d;
  int64_t v[kParamCount];
  for (int k = 0; k < kParamCount; ++k) v[k] = d.get(k);
  ParamError e;
  ASSERT_TRUE(AxisParams::check_values(v, &e)) << e.message;
  struct Case {
    int n;
    int64_t v;
    const char* message;
  };
  const Case cases[] = {
      {1, 65536 + 2000, "P1: 67536 out of range 1..65535"},  // would store as 2000
      {8, (int64_t(1) << 32) + 100, "P8: 4294967396 out of range 0..30000"},
      {10, 40000, "P10: 40000 out of range -32768..32767"},
      {11, -32769, "P11: -32769 out of range -32768..32767"},
      {15, -1, "P15: -1 out of range 0..4294967295"},
      {16, 1000000, "P16: 1000000 out of range -999999..999999"},
      {17, 256, "P17: 256 out of range 0..255"},
  };
  for (const Case& c : cases) {
    int64_t w[kParamCount];
    std::copy(v, v + kParamCount, w);
    w[c.n] = c.v;
    ParamError e2;
    EXPECT_FALSE(AxisParams::check_values(w, &e2)) << c.message;
    EXPECT_EQ(e2.message, c.message);
    EXPECT_EQ(e2.n, c.n);
  }
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell

using plc_cell::motion::AxisParams;

TEST(Params, SetByNumberMatchesTheRegisterLayout) {
  // Pn written through set() lands where FUN141's register table puts Pn.
  AxisParams p;
  const int64_t v[18] = {2, 2000, 5000, 1, 200000, 100, 1000, 3, 250, 0x0101, 2, 4, 300, 700, 4000, 0x01020304, -77, 5};
  for (int n = 0; n < 18; ++n) ASSERT_TRUE(p.set(n, v[n])) << n;
  EXPECT_FALSE(p.set(18, 1));
  EXPECT_FALSE(p.set(-1, 1));
  EXPECT_EQ(p.p9_rot, 1);
  EXPECT_EQ(p.p9_home, 1);
  uint16_t r[24] = {};
  p.to_registers(r);
  const AxisParams q = AxisParams::from_registers(r);
  uint16_t r2[24] = {};
  q.to_registers(r2);
  EXPECT_TRUE(std::equal(r, r + 24, r2));
  EXPECT_EQ(q.p16_zero, -77);
  EXPECT_EQ(q.p15_io, 0x01020304u);
  EXPECT_EQ(q.p14_ppr, 4000);
}
