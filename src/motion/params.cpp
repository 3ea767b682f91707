// FUN141 parameter table: register layout, validation, unit conversion.
#include "plc_cell/motion/params.h"

#include <cmath>
#include <limits>

namespace plc_cell {
namespace motion {

namespace {
int32_t dw(const uint16_t* r, int i) { return static_cast<int32_t>(uint32_t(r[i]) | (uint32_t(r[i + 1]) << 16)); }
void put_dw(uint16_t* r, int i, int32_t v) {
  r[i] = static_cast<uint16_t>(uint32_t(v) & 0xFFFF);
  r[i + 1] = static_cast<uint16_t>(uint32_t(v) >> 16);
}
int64_t pow10(int e) {
  int64_t p = 1;
  while (e-- > 0) p *= 10;
  return p;
}
}  // namespace

AxisParams AxisParams::from_registers(const uint16_t* r) {
  AxisParams p;
  p.p0_unit = static_cast<int16_t>(r[0]);
  p.p1_ppr = r[1];
  p.p2_per_rev = dw(r, 2);
  p.p3_res = static_cast<int16_t>(r[4]);
  p.p4_max = dw(r, 5);
  p.p5_start = dw(r, 7);
  p.p6_creep = r[9];  // unsigned: 1-65535 Ps/s
  p.p7_backlash = static_cast<int16_t>(r[10]);
  p.p8_acc_ms = static_cast<int16_t>(r[11]);
  p.p9_rot = r[12] & 0xFF;
  p.p9_home = r[12] >> 8;
  p.p10_fwd_comp = static_cast<int16_t>(r[13]);
  p.p11_bwd_comp = static_cast<int16_t>(r[14]);
  p.p12_dec_ms = static_cast<int16_t>(r[15]);
  p.p13_interp_ms = static_cast<int16_t>(r[16]);
  p.p14_ppr = dw(r, 17);
  p.p15_io = static_cast<uint32_t>(dw(r, 19));
  p.p16_zero = dw(r, 21);
  p.p17_pg0 = r[23];
  return p;
}

bool AxisParams::set(int n, int64_t v) {
  switch (n) {
    case 0: p0_unit = int(v); break;
    case 1: p1_ppr = uint32_t(v); break;
    case 2: p2_per_rev = int32_t(v); break;
    case 3: p3_res = int(v); break;
    case 4: p4_max = int32_t(v); break;
    case 5: p5_start = int32_t(v); break;
    case 6: p6_creep = int32_t(v); break;
    case 7: p7_backlash = int32_t(v); break;
    case 8: p8_acc_ms = int32_t(v); break;
    case 9: p9_rot = int(v & 0xFF); p9_home = int((v >> 8) & 0xFF); break;
    case 10: p10_fwd_comp = int32_t(v); break;
    case 11: p11_bwd_comp = int32_t(v); break;
    case 12: p12_dec_ms = int32_t(v); break;
    case 13: p13_interp_ms = int32_t(v); break;
    case 14: p14_ppr = int32_t(v); break;
    case 15: p15_io = uint32_t(v); break;
    case 16: p16_zero = int32_t(v); break;
    case 17: p17_pg0 = int(v); break;
    default: return false;
  }
  return true;
}

void AxisParams::to_registers(uint16_t* r) const {
  r[0] = static_cast<uint16_t>(p0_unit);
  r[1] = static_cast<uint16_t>(p1_ppr);
  put_dw(r, 2, p2_per_rev);
  r[4] = static_cast<uint16_t>(p3_res);
  put_dw(r, 5, p4_max);
  put_dw(r, 7, p5_start);
  r[9] = static_cast<uint16_t>(p6_creep);
  r[10] = static_cast<uint16_t>(p7_backlash);
  r[11] = static_cast<uint16_t>(p8_acc_ms);
  r[12] = static_cast<uint16_t>((p9_home << 8) | (p9_rot & 0xFF));
  r[13] = static_cast<uint16_t>(p10_fwd_comp);
  r[14] = static_cast<uint16_t>(p11_bwd_comp);
  r[15] = static_cast<uint16_t>(p12_dec_ms);
  r[16] = static_cast<uint16_t>(p13_interp_ms);
  put_dw(r, 17, p14_ppr);
  put_dw(r, 19, static_cast<int32_t>(p15_io));
  put_dw(r, 21, p16_zero);
  r[23] = static_cast<uint16_t>(p17_pg0);
}

int AxisParams::validate() const {
  const bool machine = p0_unit == 0;
  if (p0_unit < 0 || p0_unit > 2) return 1;
  if (p1_ppr < 1 || p1_ppr > 65535) return 2;
  if (p2_per_rev < 1 || p2_per_rev > 999999) return 3;
  if (p3_res < 0 || p3_res > 3) return 4;
  if (p4_max < 1 || p4_max > (machine ? 153000 : kMaxHz)) return 5;
  if (machine && (max_hz() > kMaxHz || max_hz() < 1)) return 5;
  // AMBIG-18: P5 may be 0 (start from standstill); machine units up to 15300.
  if (p5_start < 0 || p5_start > (machine ? 15300 : kMaxHz) || start_hz() > kMaxHz) return 6;
  if (p6_creep < 1 || p6_creep > (machine ? 15300 : 65535)) return 7;
  if (p7_backlash < 0 || p7_backlash > 32767) return 8;
  if (p8_acc_ms < 0 || p8_acc_ms > 30000) return 9;
  if (p9_rot < 0 || p9_rot > 1 || p9_home < 0 || p9_home > 1) return 10;
  if (p12_dec_ms < 0 || p12_dec_ms > 30000) return 13;
  if (p13_interp_ms < 0 || p13_interp_ms > 30000) return 14;
  if (p14_ppr < 0 || p14_ppr > 1999999) return 15;
  return 0;
}

int64_t AxisParams::ut_to_pulses(int64_t stroke) const {
  if (p0_unit == 1) return stroke;
  // stroke * 10^(3-P3) is in the units of B (um, mDeg, 0.1 mInch); round half away from 0.
  const __int128 num = static_cast<__int128>(stroke) * pow10(3 - p3_res) * ppr();
  const __int128 b = p2_per_rev;
  const __int128 q = (num >= 0 ? num + b / 2 : num - b / 2) / b;
  return static_cast<int64_t>(q);
}

int64_t AxisParams::pulses_to_ut(int64_t pulses) const {
  if (p0_unit == 1) return pulses;
  const __int128 num = static_cast<__int128>(pulses) * p2_per_rev;
  const __int128 den = static_cast<__int128>(pow10(3 - p3_res)) * ppr();
  const __int128 q = (num >= 0 ? num + den / 2 : num - den / 2) / den;
  return static_cast<int64_t>(q);
}

double AxisParams::speed_hz(int64_t v) const {
  if (p0_unit != 0) return static_cast<double>(v);
  return static_cast<double>(v) * 1000.0 * ppr() / (6.0 * p2_per_rev);
}

double AxisParams::acc_hz_per_s() const {
  if (p8_acc_ms == 0) return std::numeric_limits<double>::infinity();
  return max_hz() * 1000.0 / p8_acc_ms;
}

double AxisParams::dec_hz_per_s() const {
  if (p12_dec_ms == 0) return acc_hz_per_s();
  return max_hz() * 1000.0 / p12_dec_ms;
}

}  // namespace motion
}  // namespace plc_cell
