// Analog codes against the manual's worked examples (spec section 14).
#include <gtest/gtest.h>

#include "plc_cell/temp/analog_codes.h"

namespace plc_cell {
namespace temp {
namespace {

TEST(AnalogCodes, SixAdEndPointsAndMidScale) {
  const AnalogRange pm10;  // default: bipolar +-10 V
  EXPECT_EQ(ai_code14(pm10, 0.0, false), 8192);   // #1
  EXPECT_EQ(ai_code14(pm10, 10.0, false), 16383);
  EXPECT_EQ(ai_code14(pm10, 0.0, true), 0);       // #2
  EXPECT_EQ(ai_code14(pm10, 10.0, true), 8191);
  EXPECT_EQ(ai_code14(pm10, -10.0, false), 0);    // #3
  EXPECT_EQ(ai_code14(pm10, -10.0, true), -8192);
  EXPECT_EQ(ai_code14(pm10, 12.0, true), 8191);   // saturates beyond the range
  AnalogRange ma{false, true, true};              // 0..20 mA
  EXPECT_EQ(ai_code14(ma, 4.0, false), 3277);     // 16383 x 4/20 = 3276.6
  EXPECT_EQ(ai_code14(ma, 20.0, false), 16383);
  AnalogRange v5{false, false, false};            // 0..5 V
  EXPECT_EQ(ai_code14(v5, 2.5, false), 8192);
}

TEST(AnalogCodes, FormatsTwelveAndValidTwelve) {
  EXPECT_EQ(ai_register(16383, AiFormat::Valid12In14), 16380);  // #4: steps of 4
  EXPECT_EQ(ai_register(8191, AiFormat::Valid12In14), 8188);
  EXPECT_EQ(ai_register(-8192, AiFormat::Valid12In14), -8192);
  EXPECT_EQ(ai_register(-5, AiFormat::Valid12In14), -8);
  EXPECT_EQ(ai_register(16383, AiFormat::Bits12), 4095);
  EXPECT_EQ(ai_register(-8192, AiFormat::Bits12), -2048);
  EXPECT_EQ(ai_register(8191, AiFormat::Bits12), 2047);
  EXPECT_EQ(ai_register(1234, AiFormat::Valid14), 1234);
}

TEST(AnalogCodes, OffsetModeFourToTwenty) {
  EXPECT_EQ(offset_4_20(16383, false), 16383);  // #5: 16383.75 clamps
  EXPECT_EQ(offset_4_20(-4916, true), 0);       // #6
  EXPECT_EQ(offset_4_20(1000, false), 0);       // below 4 mA: 0
  AnalogRange ma{false, true, true};
  EXPECT_EQ(offset_4_20(ai_code14(ma, 12.0, false), false), 8192);  // mid of 4-20 mA: (9830-3276) x 1.25
}

TEST(AnalogCodes, OutputSignal) {
  const AnalogRange pm10;
  EXPECT_DOUBLE_EQ(ao_signal(pm10, 8191, true), 10.0);
  EXPECT_DOUBLE_EQ(ao_signal(pm10, -8192, true), -10.0);
  EXPECT_NEAR(ao_signal(pm10, 0, true), 0.0, 0.001);
  EXPECT_DOUBLE_EQ(ao_signal(pm10, 20000, false), 10.0);  // clamped to the code range
  AnalogRange ma{false, true, true};
  EXPECT_NEAR(ao_signal(ma, 3276, false), 4.0, 0.001);   // #8: 4-20 mA starts at 3276
}

}  // namespace
}  // namespace temp
}  // namespace plc_cell
