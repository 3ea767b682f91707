// FUN72 TP4, FUN73 TSTC, FUN85 TPSNS and the FB FUN86 TPCTL (fb_functions.h).
#include "plc_cell/temp/fb_functions.h"

#include <map>
#include <memory>
#include <optional>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/temp/fb_measure.h"
#include "plc_cell/temp/fb_tc_scaling.h"
#include "plc_cell/temp/tpctl_loop.h"

namespace plc_cell {
namespace temp {
namespace {

using R = OperandRole;

// R4005 byte, FB codes (B:705, B:989): 0 = 2 s (default), 1 = 4 s, 2 = 8 s, >= 3 = 1 s.
uint64_t fb_interval_us(unsigned code) { return code >= 3 ? 1000000 : uint64_t(2000000) << code; }

// Default Kc by Pl (0-10 V 60, 0-5 V 30, +-10 V 120, +-5 V 60): the same band in degC.
// R4008 is in degrees; an RTD's readings (TR) are in 0.1 degC.
TpctlUnits fb_units(int pl, bool rtd = false) {
  static const uint16_t kc[4] = {60, 30, 120, 60};
  return {4095, fb_interval_us, 999, kc[pl & 3], 17, 100, 300, rtd ? 10 : 1};
}
constexpr int kUniversal = 1;  // the FB instructions have no Md: the plain printed form

struct Fun85Info {  // what the FB FUN86 needs of the cell's FUN85
  uint32_t instance = 0;
  uint64_t last_us = 0;
  bool en = false, ready = false;
  FbPoints points;
  const uint16_t* sr = nullptr;
};

// What the FB instructions keep between scans, by instruction: the PLC's own state (its scan
// engine keeps it), so a new PLC, even one whose memory reuses a gone one's address, starts
// with none.
struct Store {
  std::map<uint32_t, FbMeasureState> measure;
  std::map<uint32_t, TpctlLoopState> loops;
  std::optional<Fun85Info> fun85;
};

// Runs f with the PLC's store. An FB instruction outside a scan engine (a bare interpreter)
// has nowhere to keep its state and does nothing.
template <class F>
void with_store(ExecContext& c, const BoundOperand* o, F f) {
  if (c.engine) f(c.engine->extensions().owned<Store>(), c, o);
}

// The operands' positions, in spec order.
namespace op72 { enum { Tp, Pl, Sm, Ym, AR, TR, WR, ERR, ALM, Count }; }
namespace op73 { enum { Tp, Pl, Sm, Ym, AR, TR, Yh, Sh, Zh, Sv, Os, PR, IR, DR, OR, WR, ERR, AO0, AO1, Count }; }
namespace op85 { enum { Tp, Pl, Zn, Yn, SR, WR, ERR, ALM, Count }; }
namespace op86 { enum { Yn, Sn, Zn, Sv, Os, PR, IR, DR, OR, WR, ERR, ALM, Count }; }

bool between(int64_t v, int64_t lo, int64_t hi) { return v >= lo && v <= hi; }

// FUN72/FUN73's measuring operands (B:556-B:600), the first seven of both; WR takes
// wr_words. The FUN73 page gives the same Tp (RTD included) and Pl as FUN72's.
OperandRules measure_rules(size_t wr, uint32_t wr_words) {
  return {
      {"Tp 0 (K), 1 (J), 2 (PT-100) or 3 (PT-1000)", [](const OperandValues& v) { return between(v[0], 0, 3); }},
      {"Pl 0 (0-10 V), 1 (0-5 V), 2 (-10..10 V) or 3 (-5..5 V)", [](const OperandValues& v) { return between(v[1], 0, 3); }},
      {"Pl 2 or 3 for an RTD (Tp 2, 3): the FB-2AH(T)4 is bipolar only",
       [](const OperandValues& v) { return !(v[0] >= kFbPt100 && between(v[0], 0, 3) && between(v[1], 0, 1)); }},
      {"0 <= Sm <= 28, a multiple of 4", [](const OperandValues& v) { return between(v[2], 0, 28) && v[2] % 4 == 0; }},
      {"Ym: 8 outputs within Y0-Y255", [](const OperandValues& v) { return v.y_fit(3, 8); }},
      {"AR: an analog input register R3840-R3903",
       [](const OperandValues& v) {
         const Address& a = v.address(4);
         return a.area == Area::R && between(a.index, 3840, 3903);
       }},
      {"TR: 4 registers", [](const OperandValues& v) { return v.words_fit(5, 4); }},
      {"WR: " + std::to_string(wr_words) + " registers", [wr, wr_words](const OperandValues& v) { return v.words_fit(wr, wr_words); }},
  };
}

const OperandRules& fun72_rules() {
  static const OperandRules r = measure_rules(op72::WR, 8);
  return r;
}

const OperandRules& fun73_rules() {
  static const OperandRules r = [] {
    using namespace op73;
    OperandRules x = measure_rules(WR, 17);
    const auto zh_ok = [](const OperandValues& v) { return between(v[Zh], 1, 32); };
    x.push_back({"0 <= Sh <= 31", [](const OperandValues& v) { return between(v[Sh], 0, 31); }});
    x.push_back({"1 <= Zh <= 32 and Sh + Zh <= 32",
                 [](const OperandValues& v) { return between(v[Zh], 1, 32) && v[Sh] + v[Zh] <= 32; }});
    x.push_back({"Sh >= Sm when Zh > 4 (the TRs of every FUN72/73 contiguous)",
                 [](const OperandValues& v) { return v[Zh] <= 4 || v[Sh] >= v[Sm]; }});
    x.push_back(tpctl_outputs_rule(Yh, Zh, 32, "Zh"));
    x.push_back(tpctl_tables_rule(Sv, Zh, 32, "Zh"));
    // Point p's temperature is TR + (p - Sm) (B:757).
    x.push_back({"the temperatures of points Sh..Sh+Zh-1 at TR + (Sh - Sm) within the registers",
                 [zh_ok](const OperandValues& v) {
                   // An Sm, Zh or Sh the rules above refuse is theirs to report.
                   if (!zh_ok(v) || !between(v[Sm], 0, 28) || v[Sm] % 4 || (v[Zh] > 4 && v[Sh] < v[Sm])) return true;
                   const int64_t first = int64_t(v.address(TR).index) + v[Sh] - v[Sm];
                   return first >= 0 && first + v[Zh] <= int64_t(Memory::word_count(v.address(TR).area));
                 }});
    return x;
  }();
  return r;
}

// FUN72/FUN73's points, from operands the rules accepted.
FbPoints measure_points(ExecContext& c, const BoundOperand* o) {
  FbPoints p;
  p.tp = int(c.get(o[0])), p.pl = int(c.get(o[1])), p.first_point = uint32_t(c.get(o[2])), p.points = 4, p.per_ai = 4;
  p.ai[0] = o[4].addr.index - 3840;
  return p;
}

bool fits_y(const BoundOperand& o, uint32_t n) { return o.addr.area == Area::Y && o.addr.index + n <= 256; }

void fun72(Store& s, ExecContext& c, const BoundOperand* o) {
  const BoundOperand &wr = o[op72::WR], &err = o[op72::ERR], &alm = o[op72::ALM];
  FbMeasureState& st = s.measure[c.instance];
  const bool ok = !broken_rule(fun72_rules(), OperandValues(c, o, op72::Count));
  const FbPoints p = measure_points(c, o);
  c.flag(err, c.en && !ok);  // "not performed and ERR on" (B:497)
  if (!ok || !c.en) {
    if (fits_y(o[3], 8)) fb_measure_stop(st, p, o[3]);
    return;
  }
  c.flag(alm, fb_measure_step(st, c, p, o[3], o[5].w, wr.w));
  wr.w[2] = uint16_t(st.step), wr.w[3] = st.cycles;  // internal: the point selected, cycles done
}

void fun73(Store& s, ExecContext& c, const BoundOperand* o) {
  using namespace op73;
  const BoundOperand &yh = o[Yh], &wr = o[WR], &err = o[ERR], &ao0 = o[AO0], &ao1 = o[AO1];
  FbMeasureState& st = s.measure[c.instance];
  TpctlLoopState& loop = s.loops[c.instance];
  const bool ok = !broken_rule(fun73_rules(), OperandValues(c, o, Count));
  const FbPoints p = measure_points(c, o);
  const int64_t sh = c.get(o[Sh]);
  const uint32_t n = ok ? uint32_t(c.get(o[Zh])) : 0;
  c.flag(err, c.en && !ok);
  if (!ok || !c.en) {
    if (fits_y(o[Ym], 8)) fb_measure_stop(st, p, o[Ym]);
    tpctl_outputs_off(loop, yh, n, true);
    return;
  }
  c.flag(ao0, fb_measure_step(st, c, p, o[Ym], o[TR].w, wr.w));
  wr.w[2] = uint16_t(st.step), wr.w[3] = st.cycles;
  if (!fb_all_measured(st, p)) return tpctl_outputs_off(loop, yh, n, false);  // PID after every point (B:727)
  const TpctlTables t{yh, o[Sv], o[Os], o[PR], o[IR], o[DR], o[OR]};
  const uint16_t* eng = o[TR].w + (sh - int64_t(p.first_point));  // TR + (Sh - Sm): within, by the rules
  const bool rtd = p.tp >= kFbPt100;
  const double pos = rtd ? 0 : fb_pos_factor(c, p);
  loop.pv.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    // The PID works on the primitive's counts (R3968 + point); the set point, in TR's
    // unit (1 degC on a thermocouple, 0.1 degC on an RTD), is turned into those counts.
    const int32_t prim = int16_t(c.mem.reg(Area::R, 3968 + uint32_t(sh) + i)), sv = int16_t(t.sv.w[i]);
    loop.pv[i] = {rtd ? fb_rtd_counts_of(c, sv, p.pl) : fb_counts_of(sv, p.pl, pos), prim, int16_t(eng[i])};
  }
  const TpctlResult r = tpctl_step(loop, c, fb_units(p.pl, rtd), t, uint32_t(sh), n, c.inputs[1], kUniversal);
  wr.w[8] = uint16_t(r.in_zone), wr.w[9] = uint16_t(r.in_zone >> 16);
  wr.w[10] = uint16_t(r.warn), wr.w[11] = uint16_t(r.warn >> 16);
  wr.w[12] = uint16_t(loop.ts_tenths);
  c.flag(ao1, r.alarm);
}

const OperandRules& fun85_rules() {
  using namespace op85;
  static const OperandRules r = {
      {"Tp 0 (K) or 1 (J)", [](const OperandValues& v) { return between(v[Tp], 0, 1); }},
      {"Pl 0 (0-10 V), 1 (0-5 V), 2 (-10..10 V) or 3 (-5..5 V)", [](const OperandValues& v) { return between(v[Pl], 0, 3); }},
      {"1 <= Zn <= 24", [](const OperandValues& v) { return between(v[Zn], 1, 24); }},
      {"Yn: 6 outputs within Y0-Y255", [](const OperandValues& v) { return v.y_fit(Yn, 6); }},
      {"SR: Zn registers", [](const OperandValues& v) { return !between(v[Zn], 1, 24) || v.words_fit(SR, uint32_t(v[Zn])); }},
      {"WR: 5 registers", [](const OperandValues& v) { return v.words_fit(WR, 5); }},
  };
  return r;
}

const OperandRules& fb_fun86_rules() {
  using namespace op86;
  static const OperandRules r = {
      {"0 <= Sn <= 23", [](const OperandValues& v) { return between(v[Sn], 0, 23); }},
      {"1 <= Zn <= 24 and Sn + Zn <= 24", [](const OperandValues& v) { return between(v[Zn], 1, 24) && v[Sn] + v[Zn] <= 24; }},
      tpctl_outputs_rule(Yn, Zn, 24, "Zn"),
      tpctl_tables_rule(Sv, Zn, 24, "Zn"),
      {"WR: 9 registers", [](const OperandValues& v) { return v.words_fit(WR, 9); }},
  };
  return r;
}

void fun85(Store& s, ExecContext& c, const BoundOperand* o) {
  // Tp Pl Zn Yn SR WR ERR ALM
  const int64_t tp = c.get(o[0]), pl = c.get(o[1]), zn = c.get(o[2]);
  const BoundOperand &yn = o[3], &sr = o[4], &wr = o[5], &err = o[6], &alm = o[7];
  FbMeasureState& st = s.measure[c.instance];
  if (!s.fun85) s.fun85.emplace();
  Fun85Info& info = *s.fun85;
  // "can only be used once" (B:865; max_uses at load): a second FUN85 executed in the same
  // scan is an error.
  const bool second = info.instance != c.instance && info.last_us == c.now_us && info.sr;
  FbPoints p;
  p.tp = int(tp), p.pl = int(pl), p.fun85 = true, p.points = int(zn), p.per_ai = 6;
  for (uint32_t g = 0; g < 4; ++g) p.ai[g] = 4 + g;  // the module is alone: its 5th-8th AI, R3844-R3847
  const bool ok = !second && !broken_rule(fun85_rules(), OperandValues(c, o, op85::Count));
  c.flag(err, c.en && !ok);
  if (!ok || !c.en) {
    if (fits_y(yn, 6)) fb_measure_stop(st, p, yn);
    if (!second) info.en = false, info.ready = false, info.instance = c.instance, info.last_us = c.now_us;
    return;
  }
  fb_fun85_init(c, int(tp), int(pl));
  c.flag(alm, fb_measure_step(st, c, p, yn, sr.w, wr.w));
  wr.w[2] = uint16_t(st.step), wr.w[3] = st.cycles;
  info = {c.instance, c.now_us, true, fb_all_measured(st, p), p, sr.w};
}

void fun86(Store& s, ExecContext& c, const BoundOperand* o) {
  // Yn Sn Zn Sv Os PR IR DR OR WR ERR ALM
  const BoundOperand &yn = o[0], &wr = o[9], &err = o[10], &alm = o[11];
  const int64_t sn = c.get(o[1]), zn = c.get(o[2]);
  TpctlLoopState& loop = s.loops[c.instance];
  const bool ok = !broken_rule(fb_fun86_rules(), OperandValues(c, o, op86::Count));
  const uint32_t n = ok ? uint32_t(zn) : 0;
  c.flag(err, c.en && !ok);
  // "FUN86 must be incorporated with FUN85 ... it must be enabled" (B:969): until then OFF.
  const bool ready = s.fun85 && s.fun85->en && s.fun85->ready && s.fun85->points.points >= sn + zn;
  if (!ok || !c.en || !ready) {
    tpctl_outputs_off(loop, yn, n, !ok || !c.en);
    if (ok && !c.en) c.flag(alm, false);
    return;
  }
  const Fun85Info& f = *s.fun85;
  const TpctlTables t{yn, o[3], o[4], o[5], o[6], o[7], o[8]};
  const double pos = fb_pos_factor(c, f.points);
  loop.pv.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t point = uint32_t(sn) + i;
    loop.pv[i] = {fb_counts_of(int16_t(t.sv.w[i]), f.points.pl, pos), int16_t(c.mem.reg(Area::R, 3968 + point)),
                  int16_t(f.sr[point])};
  }
  const TpctlResult r = tpctl_step(loop, c, fb_units(f.points.pl), t, uint32_t(sn), n, c.inputs[1], kUniversal);
  wr.w[0] = uint16_t(r.in_zone), wr.w[1] = uint16_t(r.in_zone >> 16);
  wr.w[2] = uint16_t(r.warn), wr.w[3] = uint16_t(r.warn >> 16);
  wr.w[4] = uint16_t(loop.ts_tenths);
  c.flag(alm, r.alarm);
}

FunctionSpec spec(uint16_t number, const char* mnemonic, std::vector<std::string> inputs,
                  std::vector<OperandSpec> operands) {
  FunctionSpec s;
  s.number = number;
  s.mnemonic = mnemonic;
  s.inputs = std::move(inputs);
  s.operands = std::move(operands);
  s.allow_32 = false;
  s.allow_pulse = false;
  s.always_runs = true;  // "must be executed every scan, whatever EN is"
  return s;
}

const std::vector<OperandSpec> kMeasure = {{"Tp", R::Const}, {"Pl", R::Const},    {"Sm", R::Const},
                                           {"Ym", R::BitOut}, {"AR", R::Register}, {"TR", R::Register, false, 4}};

}  // namespace

void add_fb_temperature_functions(FunctionTable& t) {
  auto ops72 = kMeasure;
  ops72.insert(ops72.end(), {{"WR", R::Register, false, 8}, {"ERR", R::BitOut, true}, {"ALM", R::BitOut, true}});
  FunctionSpec s72 = spec(72, "TP4", {"EN"}, ops72);
  s72.handler = [](ExecContext& c, const BoundOperand* o) { with_store(c, o, fun72); };
  s72.rules = fun72_rules();
  t.add(s72);

  auto ops73 = kMeasure;
  ops73.insert(ops73.end(), {{"Yh", R::BitOut},     {"Sh", R::Const},     {"Zh", R::Const},    {"Sv", R::Register},
                             {"Os", R::Register},   {"PR", R::Register},  {"IR", R::Register}, {"DR", R::Register},
                             {"OR", R::Register},   {"WR", R::Register, false, 17}, {"ERR", R::BitOut, true},
                             {"AO0", R::BitOut, true}, {"AO1", R::BitOut, true}});
  FunctionSpec s73 = spec(73, "TSTC", {"EN", "HC"}, ops73);
  s73.handler = [](ExecContext& c, const BoundOperand* o) { with_store(c, o, fun73); };
  s73.rules = fun73_rules();
  t.add(s73);

  // The operand figure is lost; the names are the text's (B:917), in its order.
  FunctionSpec s85 = spec(85, "TPSNS", {"EN"},
                          {{"Tp", R::Const}, {"Pl", R::Const}, {"Zn", R::Const}, {"Yn", R::BitOut},
                           {"SR", R::Register}, {"WR", R::Register, false, 5}, {"ERR", R::BitOut, true},
                           {"ALM", R::BitOut, true}});
  s85.handler = [](ExecContext& c, const BoundOperand* o) { with_store(c, o, fun85); };
  s85.rules = fun85_rules();
  s85.max_uses = 1;  // "can only be used once" (B:865)
  t.add(s85);

  FunctionSpec s86 = spec(86, "TPCTL", {"EN", "HC"},
                          {{"Yn", R::BitOut},   {"Sn", R::Const},    {"Zn", R::Const},    {"Sv", R::Register},
                           {"Os", R::Register}, {"PR", R::Register}, {"IR", R::Register}, {"DR", R::Register},
                           {"OR", R::Register}, {"WR", R::Register, false, 9}, {"ERR", R::BitOut, true},
                           {"ALM", R::BitOut, true}});
  s86.handler = [](ExecContext& c, const BoundOperand* o) { with_store(c, o, fun86); };
  s86.rules = fb_fun86_rules();
  t.add(s86);
}

void add_fb_only_notes(FunctionTable& t) {
  const std::string why =
      "belongs to the FB generation (FB-2AJ4/2AK4/2AH4/2AT4, FB-4AJ(K)xx); this cell is FBs. "
      "Set modules.generation: FB in the cell YAML to use it";
  t.add_unavailable(72, "TP4", why);
  t.add_unavailable(73, "TSTC", why);
  t.add_unavailable(85, "TPSNS", why);
}

}  // namespace temp
}  // namespace plc_cell
