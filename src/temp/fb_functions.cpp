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
TpctlUnits fb_units(int pl) {
  static const uint16_t kc[4] = {60, 30, 120, 60};
  return {4095, fb_interval_us, 999, kc[pl & 3], 17, 100, 300};
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

bool fits(const BoundOperand& o, uint32_t n) { return o.w && o.addr.index + n <= Memory::word_count(o.addr.area); }
bool fits_y(const BoundOperand& o, uint32_t n) { return o.addr.area == Area::Y && o.addr.index + n <= 256; }
bool is_ir(const BoundOperand& o) { return o.addr.area == Area::R && o.addr.index >= 3840 && o.addr.index <= 3903; }

// FUN72/FUN73's measuring operands: Tp Pl Sm Ym AR TR WR; false on a range error.
bool fun72_points(ExecContext& c, const BoundOperand* o, const BoundOperand& wr, uint32_t wr_words, FbPoints* p) {
  const int64_t tp = c.get(o[0]), pl = c.get(o[1]), sm = c.get(o[2]);
  p->tp = int(tp), p->pl = int(pl), p->first_point = uint32_t(sm), p->points = 4, p->per_ai = 4;
  p->ai[0] = o[4].addr.index - 3840;
  const bool rtd = tp >= 2;
  return tp >= 0 && tp <= 3 && pl >= 0 && pl <= 3 && !(rtd && pl < 2) && sm >= 0 && sm <= 28 && sm % 4 == 0 &&
         fits_y(o[3], 8) && is_ir(o[4]) && fits(o[5], 4) && fits(wr, wr_words);
}

void fun72(Store& s, ExecContext& c, const BoundOperand* o) {
  const BoundOperand &wr = o[6], &err = o[7], &alm = o[8];
  FbMeasureState& st = s.measure[c.instance];
  FbPoints p;
  const bool ok = fun72_points(c, o, wr, 8, &p);
  c.flag(err, c.en && !ok);  // "not performed and ERR on" (B:497)
  if (!ok || !c.en) {
    if (fits_y(o[3], 8)) fb_measure_stop(st, p, o[3]);
    return;
  }
  c.flag(alm, fb_measure_step(st, c, p, o[3], o[5].w, wr.w));
  wr.w[2] = uint16_t(st.step), wr.w[3] = st.cycles;  // internal: the point selected, cycles done
}

void fun73(Store& s, ExecContext& c, const BoundOperand* o) {
  // Tp Pl Sm Ym AR TR | Yh Sh Zh Sv Os PR IR DR OR WR | ERR AO0 AO1
  const BoundOperand &yh = o[6], &wr = o[15], &err = o[16], &ao0 = o[17], &ao1 = o[18];
  const int64_t sh = c.get(o[7]), zh = c.get(o[8]);
  FbMeasureState& st = s.measure[c.instance];
  TpctlLoopState& loop = s.loops[c.instance];
  FbPoints p;
  bool ok = fun72_points(c, o, wr, 17, &p) && p.tp <= kFbJ;  // PID on thermocouples only (B:686)
  ok = ok && sh >= 0 && sh <= 31 && zh >= 1 && zh <= 32 && sh + zh <= 32 && (zh <= 4 || sh >= int64_t(p.first_point)) &&
       fits_y(yh, uint32_t(zh));
  const uint32_t n = ok ? uint32_t(zh) : 0;
  for (int k = 9; k <= 14 && ok; ++k) ok = fits(o[k], n);
  // The PVs: TR + (Sh - Sm + i), the TRs of every FUN72/73 contiguous (B:757).
  const int64_t pv_first = int64_t(o[5].addr.index) + sh - int64_t(p.first_point);
  ok = ok && pv_first >= 0 && pv_first + zh <= int64_t(Memory::word_count(o[5].addr.area));
  c.flag(err, c.en && !ok);
  if (!ok || !c.en) {
    if (fits_y(o[3], 8)) fb_measure_stop(st, p, o[3]);
    tpctl_outputs_off(loop, yh, n, true);
    return;
  }
  c.flag(ao0, fb_measure_step(st, c, p, o[3], o[5].w, wr.w));
  wr.w[2] = uint16_t(st.step), wr.w[3] = st.cycles;
  if (!fb_all_measured(st, p)) return tpctl_outputs_off(loop, yh, n, false);  // PID after every point (B:727)
  const TpctlTables t{yh, o[9], o[10], o[11], o[12], o[13], o[14]};
  const uint16_t* eng = c.mem.words(o[5].addr.area) + pv_first;
  const double pos = fb_pos_factor(c, p);
  loop.pv.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    const int32_t prim = int16_t(c.mem.reg(Area::R, 3968 + uint32_t(sh) + i));
    loop.pv[i] = {fb_counts_of(int16_t(t.sv.w[i]), p.pl, pos), prim, int16_t(eng[i])};
  }
  const TpctlResult r = tpctl_step(loop, c, fb_units(p.pl), t, uint32_t(sh), n, c.inputs[1], kUniversal);
  wr.w[8] = uint16_t(r.in_zone), wr.w[9] = uint16_t(r.in_zone >> 16);
  wr.w[10] = uint16_t(r.warn), wr.w[11] = uint16_t(r.warn >> 16);
  wr.w[12] = uint16_t(loop.ts_tenths);
  c.flag(ao1, r.alarm);
}

void fun85(Store& s, ExecContext& c, const BoundOperand* o) {
  // Tp Pl Zn Yn SR WR ERR ALM
  const int64_t tp = c.get(o[0]), pl = c.get(o[1]), zn = c.get(o[2]);
  const BoundOperand &yn = o[3], &sr = o[4], &wr = o[5], &err = o[6], &alm = o[7];
  FbMeasureState& st = s.measure[c.instance];
  if (!s.fun85) s.fun85.emplace();
  Fun85Info& info = *s.fun85;
  // "can only be used once" (B:865): a second FUN85 executed in the same scan is an error.
  const bool second = info.instance != c.instance && info.last_us == c.now_us && info.sr;
  FbPoints p;
  p.tp = int(tp), p.pl = int(pl), p.fun85 = true, p.points = int(zn), p.per_ai = 6;
  for (uint32_t g = 0; g < 4; ++g) p.ai[g] = 4 + g;  // the module is alone: its 5th-8th AI, R3844-R3847
  const bool ok = !second && tp >= 0 && tp <= 1 && pl >= 0 && pl <= 3 && zn >= 1 && zn <= 24 && fits_y(yn, 6) &&
                  fits(sr, uint32_t(zn)) && fits(wr, 5);
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
  bool ok = sn >= 0 && sn <= 23 && zn >= 1 && zn <= 24 && sn + zn <= 24 && fits_y(yn, uint32_t(zn)) && fits(wr, 9);
  const uint32_t n = ok ? uint32_t(zn) : 0;
  for (int k = 3; k <= 8 && ok; ++k) ok = fits(o[k], n);
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
  t.add(s72);

  auto ops73 = kMeasure;
  ops73.insert(ops73.end(), {{"Yh", R::BitOut},     {"Sh", R::Const},     {"Zh", R::Const},    {"Sv", R::Register},
                             {"Os", R::Register},   {"PR", R::Register},  {"IR", R::Register}, {"DR", R::Register},
                             {"OR", R::Register},   {"WR", R::Register, false, 17}, {"ERR", R::BitOut, true},
                             {"AO0", R::BitOut, true}, {"AO1", R::BitOut, true}});
  FunctionSpec s73 = spec(73, "TSTC", {"EN", "HC"}, ops73);
  s73.handler = [](ExecContext& c, const BoundOperand* o) { with_store(c, o, fun73); };
  t.add(s73);

  // The operand figure is lost; the names are the text's (B:917), in its order.
  FunctionSpec s85 = spec(85, "TPSNS", {"EN"},
                          {{"Tp", R::Const}, {"Pl", R::Const}, {"Zn", R::Const}, {"Yn", R::BitOut},
                           {"SR", R::Register}, {"WR", R::Register, false, 5}, {"ERR", R::BitOut, true},
                           {"ALM", R::BitOut, true}});
  s85.handler = [](ExecContext& c, const BoundOperand* o) { with_store(c, o, fun85); };
  t.add(s85);

  FunctionSpec s86 = spec(86, "TPCTL", {"EN", "HC"},
                          {{"Yn", R::BitOut},   {"Sn", R::Const},    {"Zn", R::Const},    {"Sv", R::Register},
                           {"Os", R::Register}, {"PR", R::Register}, {"IR", R::Register}, {"DR", R::Register},
                           {"OR", R::Register}, {"WR", R::Register, false, 9}, {"ERR", R::BitOut, true},
                           {"ALM", R::BitOut, true}});
  s86.handler = [](ExecContext& c, const BoundOperand* o) { with_store(c, o, fun86); };
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
