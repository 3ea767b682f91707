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

namespace {
// Manual section 11.6. P5 may be 0 (start from standstill, AMBIG-18); P9 is two bytes
// of 0/1 (checked byte by byte below).
constexpr ParamRange kRanges[kParamCount] = {
    {0, 1, 0, 2, 0, 2},
    {1, 2, 1, 65535, 1, 65535},
    {2, 3, 1, 999999, 1, 999999},
    {3, 4, 0, 3, 0, 3},
    {4, 5, 1, kMaxHz, 1, 153000},
    {5, 6, 0, kMaxHz, 0, 15300},
    {6, 7, 1, 65535, 1, 15300},
    {7, 8, 0, 32767, 0, 32767},
    {8, 9, 0, 30000, 0, 30000},
    {9, 10, 0, 0x0101, 0, 0x0101},
    {10, 0, -32768, 32767, -32768, 32767},
    {11, 0, -32768, 32767, -32768, 32767},
    {12, 13, 0, 30000, 0, 30000},
    {13, 14, 0, 30000, 0, 30000},
    {14, 15, 0, 1999999, 0, 1999999},
    {15, 0, 0, 0xFFFFFFFFLL, 0, 0xFFFFFFFFLL},
    {16, 0, -999999, 999999, -999999, 999999},
    {17, 0, 0, 255, 0, 255},
};

bool bad(const ParamRange& r, int64_t v, const std::string& why, ParamError* e) {
  if (e) {
    e->n = r.n;
    e->code = r.code;
    e->value = v;
    e->message = "P" + std::to_string(r.n) + ": " + why;
  }
  return false;
}
}  // namespace

const ParamRange& param_range(int n) { return kRanges[n < 0 || n >= kParamCount ? 0 : n]; }

bool check_param(int n, int64_t v, bool machine, ParamError* e) {
  if (n < 0 || n >= kParamCount) {
    if (e) *e = {n, 0, v, "P" + std::to_string(n) + ": no such parameter (P0..P17)"};
    return false;
  }
  const ParamRange& r = kRanges[n];
  const int64_t lo = machine ? r.machine_lo : r.lo, hi = machine ? r.machine_hi : r.hi;
  if (n == 9 && (v < 0 || v > 0xFFFF || (v & 0xFF) > 1 || (v >> 8) > 1))
    return bad(r, v, std::to_string(v) + " out of range: low byte (P9-0) 0..1, high byte (P9-1) 0..1 "
                     "(0000H, 0001H, 0100H, 0101H)", e);
  if (v < lo || v > hi)
    return bad(r, v, std::to_string(v) + " out of range " + std::to_string(lo) + ".." + std::to_string(hi) +
                         (machine && (lo != r.lo || hi != r.hi) ? " (machine units, P0 = 0)" : ""),
               e);
  return true;
}

int64_t AxisParams::get(int n) const {
  switch (n) {
    case 0: return p0_unit;
    case 1: return p1_ppr;
    case 2: return p2_per_rev;
    case 3: return p3_res;
    case 4: return p4_max;
    case 5: return p5_start;
    case 6: return p6_creep;
    case 7: return p7_backlash;
    case 8: return p8_acc_ms;
    case 9: return (int64_t(p9_home) << 8) | p9_rot;
    case 10: return p10_fwd_comp;
    case 11: return p11_bwd_comp;
    case 12: return p12_dec_ms;
    case 13: return p13_interp_ms;
    case 14: return p14_ppr;
    case 15: return p15_io;
    case 16: return p16_zero;
    case 17: return p17_pg0;
    default: return 0;
  }
}

int AxisParams::validate(ParamError* e) const {
  ParamError local;
  ParamError* err = e ? e : &local;
  const bool machine = p0_unit == 0;
  for (const ParamRange& r : kRanges) {
    if (r.code == 0) continue;  // no error code in the manual: FUN141 takes the register as it is
    if (!check_param(r.n, get(r.n), machine, err)) return r.code;
    // Machine speeds must also come out within the pulse generator's range.
    if (machine && r.n == 4 && (max_hz() > kMaxHz || max_hz() < 1))
      return bad(r, p4_max, std::to_string(p4_max) + " (machine units) is " + std::to_string(std::llround(max_hz())) +
                                " Hz, outside 1.." + std::to_string(kMaxHz) + " Hz", err), 5;
    if (r.n == 5 && start_hz() > kMaxHz)
      return bad(r, p5_start, std::to_string(p5_start) + " (machine units) is " + std::to_string(std::llround(start_hz())) +
                                  " Hz, above " + std::to_string(kMaxHz) + " Hz", err), 6;
  }
  return 0;
}

bool AxisParams::check_values(const int64_t* v, ParamError* e) {
  std::vector<std::pair<int, int64_t>> all;
  for (int n = 0; n < kParamCount; ++n) all.push_back({n, v[n]});
  AxisParams p;
  return AxisParams().updated(all, &p, e);
}

bool AxisParams::updated(const std::vector<std::pair<int, int64_t>>& changes, AxisParams* out, ParamError* e) const {
  bool machine = p0_unit == 0;
  for (const auto& c : changes)
    if (c.first == 0) machine = c.second == 0;
  for (const auto& c : changes)
    if (!check_param(c.first, c.second, machine, e)) return false;
  AxisParams p = *this;
  for (const auto& c : changes) p.set(c.first, c.second);
  if (p.validate(e) != 0) return false;
  *out = p;
  return true;
}

bool param_changes(const std::vector<std::string>& names, const std::vector<int64_t>& values,
                   std::vector<std::pair<int, int64_t>>* out, std::string* why) {
  out->clear();
  if (names.empty()) {
    if (values.size() != size_t(kParamCount)) {
      *why = "give the 18 values P0..P17 in order, or names with their values (names: [p8], values: [100]); got " +
             std::to_string(values.size()) + " values and no names";
      return false;
    }
    for (int n = 0; n < kParamCount; ++n) out->push_back({n, values[size_t(n)]});
    return true;
  }
  if (names.size() != values.size()) {
    *why = std::to_string(names.size()) + " names but " + std::to_string(values.size()) + " values: one value per name";
    return false;
  }
  for (size_t i = 0; i < names.size(); ++i) {
    const int n = param_number(names[i]);
    if (n < 0) {
      *why = "'" + names[i] + "': no such parameter (p0 ... p17)";
      return false;
    }
    for (const auto& c : *out)
      if (c.first == n) {
        *why = "P" + std::to_string(n) + " given twice";
        return false;
      }
    out->push_back({n, values[i]});
  }
  return true;
}

int param_number(const std::string& key) {
  if (key.size() < 2 || key.size() > 3 || (key[0] != 'p' && key[0] != 'P')) return -1;
  for (size_t i = 1; i < key.size(); ++i)
    if (key[i] < '0' || key[i] > '9') return -1;
  if (key.size() == 3 && key[1] == '0') return -1;  // p08
  const int n = std::stoi(key.substr(1));
  return n < kParamCount ? n : -1;
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
