// FUN72/73/85's multiplexed measurement (fb_measure.h).
#include "plc_cell/temp/fb_measure.h"

#include <algorithm>
#include <cmath>

#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/memory.h"
#include "plc_cell/temp/fb_modules.h"
#include "plc_cell/temp/fb_tc_scaling.h"
#include "plc_cell/temp/rtd.h"
#include "plc_cell/temp/temperature_cell.h"
#include "set_output.h"

namespace plc_cell {
namespace temp {
namespace {

constexpr uint32_t kPrimitives = 3968;  // R3968 TP0 .. R3999 TP31
// An RTD's primitive when its AI is past the ceiling: above the 900.0 degC line-broken
// threshold (plc_cell's value; the manual has "the line broken value" only).
constexpr int32_t kRtdBroken = 9999;

uint16_t reg(const ExecContext& c, uint32_t r) { return c.mem.reg(Area::R, r); }

int dos(const FbPoints& p) { return p.per_ai == 6 ? 6 : 8; }

// The DO pattern of step k: Ym+2k and Ym+2k+1 (FB-2A?4), Yn+k (FB-4AJ(K)xx).
void select(const FbPoints& p, const BoundOperand& ym, int k) {
  for (int b = 0; b < dos(p); ++b) set_y(ym, uint32_t(b), k >= 0 && (p.per_ai == 6 ? b == k : b / 2 == k));
}

// The RTD firmware: AI -> resistance over the span's range -> degC x 10 by the curve
// R4020's high byte names (0 DIN, 1 JIS).
int32_t rtd_primitive(int32_t ai, bool pt1000, bool jis, bool span10) {
  if (ai > kFbIrCeiling) return kRtdBroken;
  const std::string alpha = jis ? "JIS" : "DIN";
  const RtdCurve k = rtd_curve(pt1000 ? 1000 : 100, alpha);
  double lo, hi;
  fb_rtd_range(alpha, span10, &lo, &hi);
  const double rlo = rtd_resistance(k, lo), rhi = rtd_resistance(k, hi);
  const double r = rlo + (ai + 2048.0) / (kFbIrCeiling + 2048.0) * (rhi - rlo);
  return int32_t(std::lround(10.0 * rtd_temperature(k, r)));
}

}  // namespace

void fb_fun85_init(ExecContext& c, int tp, int pl) {
  const uint16_t sig = uint16_t(0x80 | tp << 2 | pl);  // plc_cell's signature: nonzero, Tp and Pl
  Memory& m = c.mem;
  if ((m.reg(Area::R, treg::kFbFun85) & 0xFF) == sig) return;
  const FbTc t = tp == kFbK ? FbTc::K : FbTc::J;
  m.set_reg(Area::R, treg::kFbFun85, sig);
  m.set_reg(Area::R, treg::kFbFun85 + 1, uint16_t(fb_default_pos_factor(t, pl, true)));
  m.set_reg(Area::R, treg::kFbFun85 + 2, uint16_t(fb_default_neg_factor(t)));
  m.set_reg(Area::R, treg::kFbFun85 + 3, fb_span10(pl) ? 901 : 451);
  m.set_reg(Area::R, treg::kFbFun85 + 4, 333);
}

uint32_t fb_slot_ms(const ExecContext& c, const FbPoints& p) {
  return std::max<uint32_t>(1, reg(c, p.fun85 ? treg::kFbFun85 + 4 : treg::kFbSlotMs));
}

double fb_pos_factor(const ExecContext& c, const FbPoints& p) {
  if (p.fun85) return reg(c, treg::kFbFun85 + 1);
  // FUN72/73: R4016 (K) / R4018 (J) is the 10 V factor; the 5 V spans halve it, as
  // FUN85's defaults do (124 = 248 / 2), so one register serves modules of both spans.
  const double f = reg(c, treg::kFbFactors + (p.tp == kFbK ? 0 : 2));
  return fb_span10(p.pl) ? f : f / 2;
}

int32_t fb_counts_of(int32_t degc, int pl, double pos) {
  return int32_t(std::lround(degc * 1024.0 / ((fb_bipolar(pl) ? 2.0 : 1.0) * std::max(pos, 1.0))));
}

int32_t fb_rtd_counts_of(const ExecContext& c, int32_t tenths, int pl) {
  double lo, hi;
  fb_rtd_range(reg(c, treg::kFbRtd) >> 8 == 1 ? "JIS" : "DIN", fb_span10(pl), &lo, &hi);
  return int32_t(std::clamp(std::round((tenths - lo * 10) / ((hi - lo) * 10) * 4095), 0.0, 4095.0));
}

void fb_measure_stop(FbMeasureState& st, const FbPoints& p, const BoundOperand& ym) {
  select(p, ym, -1);
  st.running = false;
}

bool fb_measure_step(FbMeasureState& st, ExecContext& c, const FbPoints& p, const BoundOperand& ym, uint16_t* tr,
                     uint16_t* wr) {
  const uint64_t now = c.now_us, slot = uint64_t(fb_slot_ms(c, p)) * 1000;
  // The instruction must run every scan (B:460): a scan without it loses the
  // conversion in progress, and the cycle restarts at point 0.
  if (st.running && (st.last_us != now - c.dt_us || now < st.last_us)) st.running = false;
  st.last_us = now;
  if (st.window.size() != size_t(p.points)) st.window.assign(size_t(p.points), {});
  if (!st.running) {
    st.running = true;
    st.step = 0;
    st.t_select = now;
    select(p, ym, 0);
  } else if (now - st.t_select >= slot) {
    const bool tc = p.tp <= kFbJ;
    const int avg_code = p.fun85 ? reg(c, treg::kFbFun85) >> 8 : reg(c, treg::kFbAveraging);
    const size_t avg = size_t(1) << std::clamp(avg_code, 0, 4);  // 0 none, 1 = 2 .. 4 = 16 samples
    const uint32_t installed = reg(c, treg::kInstalled) | uint32_t(reg(c, treg::kInstalled + 1)) << 16;
    const uint16_t r4020 = reg(c, treg::kFbRtd);
    for (int g = 0; g * p.per_ai + st.step < p.points && g < 4; ++g) {
      const int i = g * p.per_ai + st.step;
      const uint32_t point = p.first_point + uint32_t(i);
      const int32_t ai = int16_t(c.mem.reg(Area::R, 3840 + p.ai[g]));
      auto& w = st.window[size_t(i)];
      int32_t prim = tc ? fb_primitive(ai, p.pl) : rtd_primitive(ai, p.tp == kFbPt1000, r4020 >> 8 == 1, fb_span10(p.pl));
      const bool over = tc ? ai > kFbIrCeiling : prim == kRtdBroken;  // the line-broken zone: not averaged
      if (over) {
        w.clear();
      } else {  // moving average of the last avg primitives
        w.push_back(prim);
        if (w.size() > avg) w.erase(w.begin());
        double sum = 0;
        for (int32_t v : w) sum += v;
        prim = int32_t(std::lround(sum / double(w.size())));
      }
      int32_t eng, tp_reg;
      bool broken;
      if (tc) {
        eng = fb_tc_engineering(prim, p.pl, fb_pos_factor(c, p), reg(c, p.fun85 ? treg::kFbFun85 + 2 : treg::kFbFactors + (p.tp == kFbK ? 1 : 3)));
        broken = p.fun85 ? eng >= int16_t(reg(c, treg::kFbFun85 + 3)) : eng > fb_line_broken_above(p.pl);
        tp_reg = prim;
      } else {  // 0.1 degC, then rescaled to 0..4095 over the span's range
        eng = int32_t(std::lround(prim * double(reg(c, treg::kFbRtdFactors + (p.tp == kFbPt1000 ? 1 : 0))) / 1024.0));
        broken = eng > 9000;  // "greater than 900.0 degC"
        tp_reg = fb_rtd_counts_of(c, eng, p.pl);
      }
      if (!(installed >> point & 1u)) eng = 0, tp_reg = 0, broken = false, w.clear();  // not installed: 0, no check
      tr[i] = uint16_t(std::clamp(eng, -32768, 32767));
      c.mem.set_reg(Area::R, kPrimitives + point, uint16_t(tp_reg));
      uint16_t& bits = wr[i / 16];
      bits = uint16_t(broken ? bits | 1u << (i % 16) : bits & ~(1u << (i % 16)));
      st.measured |= 1u << i;
    }
    st.step = (st.step + 1) % p.per_ai;
    if (st.step == 0) ++st.cycles;
    // Keep the exact period while scans are shorter than a slot.
    st.t_select = now - st.t_select < 2 * slot ? st.t_select + slot : now;
    select(p, ym, st.step);
  }
  return wr[0] != 0 || (p.points > 16 && wr[1] != 0);
}

}  // namespace temp
}  // namespace plc_cell
