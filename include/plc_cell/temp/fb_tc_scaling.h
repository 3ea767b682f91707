#pragma once
// The older FB-series temperature modules' arithmetic (FB-2AJ(K)4 with FUN72/FUN73,
// FB-4AJ(K)xx with FUN85; second source chapter 20, B:318-B:440, B:876-B:922): IR ->
// primitive value -> engineering value with the R4016-R4019 / R4001-R4002 factors,
// the line-broken thresholds and the update periods. Pure math, used by the emulated
// FB modules (fb_modules.h) and FUN72/73/85/86-FB (fb_functions.h).
#include <cstdint>

namespace plc_cell {
namespace temp {

enum class FbTc : uint8_t { K, J };  // FUN72/FUN85 Tp 0 = K, 1 = J

// Pl (polarity and span): 0 = 0-10 V, 1 = 0-5 V, 2 = -10..10 V, 3 = -5..5 V.
inline bool fb_bipolar(int pl) { return pl >= 2; }
inline bool fb_span10(int pl) { return pl == 0 || pl == 2; }

// The module's IR -> primitive: unipolar reads -2048..2047 for 0..full, so + 2048
// (B:318); bipolar as read.
int32_t fb_primitive(int32_t ir, int pl);

// Primitive -> degC (B:388-B:416): positive: prim x factor / 1024 (unipolar) or
// x 2 x factor / 1024 (bipolar); negative: prim x 2 x neg / 1024 on +-10 V, x neg / 1024
// on +-5 V. Rounded to the nearest degree (the manual's TC resolution is 1 degC; the
// rounding rule is not given).
// pos_factor is a double: FUN72 on a 5 V span uses R4016 / 2 (docs, "FB generation").
int32_t fb_tc_engineering(int32_t primitive, int pl, double pos_factor, double neg_factor);

// "the content of IR at most it can reach 1842. For the scale exceeding 1842, it is
// treated for line broken check only" (B:275). An open input reads full scale, 2047.
constexpr int32_t kFbIrCeiling = 1842, kFbIrOpen = 2047;

// Default factors: FUN72 R4016-R4019 (K 248/286, J 240/280); FUN85 R4001/R4002 use half
// the positive factor on the 5 V spans (K 124, J 120).
int32_t fb_default_pos_factor(FbTc t, int pl, bool fun85);
int32_t fb_default_neg_factor(FbTc t);

// The reading is "line broken" above this (degC; the FB-2AJ(K)4 table B:520): K 900 / 450,
// J 900 / 450 on the 10 V / 5 V spans.
int32_t fb_line_broken_above(int pl);

// Update period in ms: FUN72/73 R4014 ms per point x 4 points; FUN85 R4004 x 6.
inline uint32_t fb_update_ms_fun72(uint32_t r4014) { return r4014 * 4; }
inline uint32_t fb_update_ms_fun85(uint32_t r4004) { return r4004 * 6; }

}  // namespace temp
}  // namespace plc_cell
