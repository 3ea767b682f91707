// The FB-series temperature arithmetic against the spec's worked examples #14-#22.
#include <gtest/gtest.h>

#include "plc_cell/temp/fb_tc_scaling.h"

namespace plc_cell {
namespace temp {
namespace {

TEST(FbTcScaling, WorkedExamples) {
  // #14: K unipolar, R4016 248, primitive 2048 -> 496 degC.
  EXPECT_EQ(fb_tc_engineering(2048, 0, 248, 286), 496);
  // #15: K bipolar, primitive 1000 -> 484.375 -> 484.
  EXPECT_EQ(fb_tc_engineering(1000, 2, 248, 286), 484);
  // #16: K +-10 V, R4017 286, primitive -300 -> -167.58 -> -168.
  EXPECT_EQ(fb_tc_engineering(-300, 2, 248, 286), -168);
  // #17: K +-5 V, primitive -300 -> -83.79 -> -84.
  EXPECT_EQ(fb_tc_engineering(-300, 3, 248, 286), -84);
  // #18: IR 1842 on +-10 V K -> 892 degC, below the 900 threshold: valid.
  const int32_t t18 = fb_tc_engineering(fb_primitive(1842, 2), 2, 248, 286);
  EXPECT_EQ(t18, 892);
  EXPECT_LE(t18, fb_line_broken_above(2));
  // #19: IR 1842 unipolar 10 V K -> primitive 3890 -> 942 degC: line broken.
  EXPECT_EQ(fb_primitive(1842, 0), 3890);
  const int32_t t19 = fb_tc_engineering(3890, 0, 248, 286);
  EXPECT_EQ(t19, 942);
  EXPECT_GT(t19, fb_line_broken_above(0));
  // #20: FUN85 5 V K bipolar, R4001 124: primitive 1000 -> 242.2 -> 242.
  EXPECT_EQ(fb_default_pos_factor(FbTc::K, 3, true), 124);
  EXPECT_EQ(fb_tc_engineering(1000, 3, 124, 286), 242);
  // Unipolar 0 V reads -2048 -> primitive 0.
  EXPECT_EQ(fb_primitive(-2048, 1), 0);
  EXPECT_EQ(fb_default_pos_factor(FbTc::J, 1, false), 240);
  EXPECT_EQ(fb_default_pos_factor(FbTc::J, 1, true), 120);
  EXPECT_EQ(fb_default_neg_factor(FbTc::J), 280);
  EXPECT_EQ(fb_line_broken_above(1), 450);
}

TEST(FbTcScaling, UpdatePeriods) {
  // #21: R4014 500 / 250 / 1000 / 2000 ms -> 2 / 1 / 4 / 8 s.
  EXPECT_EQ(fb_update_ms_fun72(500), 2000u);
  EXPECT_EQ(fb_update_ms_fun72(250), 1000u);
  EXPECT_EQ(fb_update_ms_fun72(1000), 4000u);
  EXPECT_EQ(fb_update_ms_fun72(2000), 8000u);
  // #22: R4004 333 / 166 / 666 / 1333 ms -> 1998 / 996 / 3996 / 7998 ms.
  EXPECT_EQ(fb_update_ms_fun85(333), 1998u);
  EXPECT_EQ(fb_update_ms_fun85(166), 996u);
  EXPECT_EQ(fb_update_ms_fun85(666), 3996u);
  EXPECT_EQ(fb_update_ms_fun85(1333), 7998u);
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
