// FUN86 TPCTL: PID temperature control of up to 32 points with time-proportional
// (PWM) outputs, in-zone bits, and high-temperature / heater-open warnings.
#include "plc_cell/temp/tpctl.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/temp/temperature_cell.h"
#include "plc_cell/temp/tpctl_loop.h"

namespace plc_cell {
namespace temp {

double TpctlPoint::solve(int32_t sv, int32_t pv, int kc, int ki, int td, int ts, bool heating, int method) {
  const double sign = heating ? 1.0 : -1.0;
  const double e = sign * double(sv - pv);
  const double p = kc * e;
  // Ki repeats/min x Ts: Ki/100 per 60 s, Ts/10 s  ->  Kc e Ki Ts / 60000 per solve.
  const double di = kc * e * ki * ts / 60000.0;
  // Td/100 min = 0.6 Td s; dPV per Ts/10 s  ->  Kc 6 Td dPV / Ts.
  const double d = primed ? -sign * kc * 6.0 * td * double(pv - prev_pv) / ts : 0.0;
  prev_pv = pv;
  primed = true;
  const double free = p + d;  // what the output would be without the integral
  const double fs = full_scale;
  const bool in_band = free > -fs && free < fs;
  if (method == 1 || in_band) {
    const double m = free + integral + di;
    // Conditional integration: no accumulation that drives a saturated output further.
    if (!((m > fs && di > 0) || (m < 0 && di < 0))) integral += di;
  }
  integral = std::clamp(integral, -fs, fs);
  output = std::clamp(free + integral, 0.0, fs);
  return output;
}

namespace {

using R = OperandRole;

// The loops of one PLC, by instruction: the PLC's own state (its scan engine keeps it), so
// a new PLC, even one whose memory reuses a gone one's address, starts with none.
struct TpctlLoops {
  std::map<uint32_t, TpctlLoopState> by_instance;
};

// The start of the PVs: R4004 when R4003 = A55AH, else the configured readings.
const uint16_t* pv_source(const ExecContext& c, uint32_t needed, bool* ready) {
  const Memory& mem = c.mem;
  *ready = true;
  if (mem.reg(Area::R, treg::kPvFromR4004) == 0xA55A) {
    const uint32_t a = mem.reg(Area::R, treg::kPvStart);
    if (a >= 10000 && a + needed <= 13840) return mem.words(Area::R) + (a - 10000);
    if (a >= 20000 && a + needed <= 24000) return mem.words(Area::D) + (a - 20000);
  }
  const TemperatureCell* cell = temperature_cell_of(c.engine);
  if (!cell) return nullptr;
  *ready = cell->all_read();  // FUN86 runs only after every channel has been read (A:7136)
  const Address& r = cell->config().readings;
  if (r.index + needed > Memory::word_count(r.area)) return nullptr;
  return mem.words(r.area) + r.index;
}

// Md Yn Sn Zn Sv Os PR IR DR OR WR ERR ALM
constexpr size_t kMd = 0, kYn = 1, kSn = 2, kZn = 3, kSv = 4, kWr = 10, kOperands = 13;

const OperandRules& rules() {
  static const OperandRules r = {
      {"Md 0 or 1", [](const OperandValues& v) { return v[kMd] == 0 || v[kMd] == 1; }},
      {"0 <= Sn <= 31", [](const OperandValues& v) { return v[kSn] >= 0 && v[kSn] <= 31; }},
      {"1 <= Zn <= 32 and Sn + Zn <= 32",
       [](const OperandValues& v) { return v[kZn] >= 1 && v[kZn] <= 32 && v[kSn] + v[kZn] <= 32; }},
      tpctl_outputs_rule(kYn, kZn, 32, "Zn"),
      tpctl_tables_rule(kSv, kZn, 32, "Zn"),
      {"WR: 9 registers", [](const OperandValues& v) { return v.words_fit(kWr, 9); }},
  };
  return r;
}

const TpctlUnits kFbsUnits{kTpctlFullScale, fbs_interval_us, 9999, 110, 17, 50, 60};

void run(ExecContext& c, const BoundOperand* o) {
  const int md = int(c.get(o[0]));
  const BoundOperand& yn = o[1];
  const int64_t sn = c.get(o[2]), zn = c.get(o[3]);
  const TpctlTables t{yn, o[4], o[5], o[6], o[7], o[8], o[9]};
  const BoundOperand &wr = o[10], &err = o[11], &alm = o[12];

  if (!c.engine) return c.flag(err, true);  // a loop's state lives in its PLC's scan engine
  TpctlLoopState& st = c.engine->extensions().owned<TpctlLoops>().by_instance[c.instance];
  const bool tables_ok = !broken_rule(rules(), OperandValues(c, o, kOperands));
  const uint32_t n = tables_ok ? uint32_t(zn) : 0;
  bool ready = false;
  const uint16_t* pvs = tables_ok ? pv_source(c, uint32_t(sn + zn), &ready) : nullptr;

  if (!c.en || !pvs) {
    // EN off (or an error): outputs off; the next EN = 1 takes R4005 afresh (Note 1).
    tpctl_outputs_off(st, yn, n, true);
    c.flag(err, c.en && !pvs);
    if (c.en && !pvs) c.flag(alm, false);
    return;
  }
  c.flag(err, false);
  if (!ready) return tpctl_outputs_off(st, yn, n, false);
  st.pv.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    const int32_t pv = int16_t(pvs[uint32_t(sn) + i]), sv = int16_t(t.sv.w[i]);
    st.pv[i] = {sv, pv, pv};
  }
  const TpctlResult r = tpctl_step(st, c, kFbsUnits, t, uint32_t(sn), n, c.inputs[1], md);
  wr.w[0] = uint16_t(r.in_zone);
  wr.w[1] = uint16_t(r.in_zone >> 16);
  wr.w[2] = uint16_t(r.warn);
  wr.w[3] = uint16_t(r.warn >> 16);
  wr.w[4] = uint16_t(st.ts_tenths);  // internal: the solution interval in use (0.1 s)
  c.flag(alm, r.alarm);
}

}  // namespace

uint64_t fbs_interval_us(unsigned code) { return uint64_t(1000000) << std::min(code, 5u); }  // 1, 2, 4 .. 32 s

void add_tpctl_function(FunctionTable& t) {
  FunctionSpec s;
  s.number = 86;
  s.mnemonic = "TPCTL";
  s.inputs = {"EN", "HC"};
  s.operands = {{"Md", R::Const},     {"Yn", R::BitOut},   {"Sn", R::Const},    {"Zn", R::Const},
                {"Sv", R::Register},  {"Os", R::Register}, {"PR", R::Register}, {"IR", R::Register},
                {"DR", R::Register},  {"OR", R::Register}, {"WR", R::Register, false, 9},
                {"ERR", R::BitOut, true}, {"ALM", R::BitOut, true}};
  s.allow_32 = false;
  s.allow_pulse = false;
  s.always_runs = true;  // sees EN fall: the outputs go OFF
  s.handler = run;
  s.rules = rules();
  t.add(s);
}

}  // namespace temp
}  // namespace plc_cell
